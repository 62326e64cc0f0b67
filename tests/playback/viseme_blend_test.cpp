// Coarticulation of mouth shapes: golden values computed by hand from the dominance functions,
// continuity of the blend (bounded change between samples) and poses never exceeded, over
// seeded random cue sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "avar/playback/offline/viseme_blend.hpp"

namespace avar::playback {
namespace {

VisemeTable viseme_test_table() {
  VisemeTable t;
  t.channels = {"jaw", "lips"};
  t.shapes = {"X", "A", "D"};
  t.poses = {{0, 0}, {0, 10}, {20, 0}};
  t.dominance = {1, 1, 1};
  return t;
}

VisemeCue viseme_cue(double start, double end, const char* shape) {
  VisemeCue c;
  c.start = start;
  c.end = end;
  c.shape = shape;
  return c;
}

TEST(VisemeBlend, GoldenValuesFromTheDominanceFunctions) {
  const std::vector<VisemeCue> cues = {viseme_cue(0, 0.2, "X"), viseme_cue(0.2, 0.4, "D"), viseme_cue(0.4, 0.5, "A"),
                                       viseme_cue(0.5, 1.0, "X")};
  const CoarticulationOptions o;  // rise = decay = 50 ms
  // t = 0.3 s, inside D: X1 ended 0.1 s ago (e^-2), A starts in 0.1 s (e^-2), X2 in 0.2 s (e^-4).
  const double w = 1 + 2 * std::exp(-2.0) + std::exp(-4.0);
  auto v = blend_visemes_at(cues, viseme_test_table(), o, 0.3);
  EXPECT_NEAR(v[0], 20 / w, 1e-12);
  EXPECT_NEAR(v[1], 10 * std::exp(-2.0) / w, 1e-12);
  // t = 0.2 s, the X-D boundary: both at full dominance; A 0.2 s ahead (e^-4), X2 0.3 s (e^-6).
  const double w2 = 2 + std::exp(-4.0) + std::exp(-6.0);
  v = blend_visemes_at(cues, viseme_test_table(), o, 0.2);
  EXPECT_NEAR(v[0], 20 / w2, 1e-12);
  EXPECT_NEAR(v[1], 10 * std::exp(-4.0) / w2, 1e-12);
  // t = 0.45 s, inside A: D ended 0.05 s ago (e^-1), X1 0.25 s (e^-5); X2 starts in 0.05 s (e^-1).
  const double w3 = 1 + 2 * std::exp(-1.0) + std::exp(-5.0);
  v = blend_visemes_at(cues, viseme_test_table(), o, 0.45);
  EXPECT_NEAR(v[0], 20 * std::exp(-1.0) / w3, 1e-12);
  EXPECT_NEAR(v[1], 10 / w3, 1e-12);
  // t = 0.95 s, deep in the last rest: A ended 0.45 s ago (e^-9), D 0.55 s (e^-11), X1 0.75 s (e^-15).
  const double w4 = 1 + std::exp(-9.0) + std::exp(-11.0) + std::exp(-15.0);
  v = blend_visemes_at(cues, viseme_test_table(), o, 0.95);
  EXPECT_NEAR(v[0], 20 * std::exp(-11.0) / w4, 1e-15);
  EXPECT_NEAR(v[1], 10 * std::exp(-9.0) / w4, 1e-15);
}

TEST(VisemeBlend, DominanceAndAsymmetricTimeConstants) {
  VisemeTable t = viseme_test_table();
  t.dominance = {1, 3, 1};  // A (closed lips) dominates
  CoarticulationOptions o;
  o.rise_s = 0.1;
  o.decay_s = 0.02;
  const std::vector<VisemeCue> cues = {viseme_cue(0, 0.2, "D"), viseme_cue(0.2, 0.3, "A")};
  // t = 0.15 s: D inside (1); A 0.05 s ahead: 3 e^-0.5.
  auto v = blend_visemes_at(cues, t, o, 0.15);
  const double wa = 3 * std::exp(-0.5);
  EXPECT_NEAR(v[0], 20 / (1 + wa), 1e-12);
  EXPECT_NEAR(v[1], 10 * wa / (1 + wa), 1e-12);
  // t = 0.32 s: A ended 0.02 s ago (3 e^-1); D ended 0.12 s ago (e^-6).
  v = blend_visemes_at(cues, t, o, 0.32);
  const double wd = std::exp(-6.0), wa2 = 3 * std::exp(-1.0);
  EXPECT_NEAR(v[0], 20 * wd / (wd + wa2), 1e-12);
}

TEST(VisemeBlend, ContinuousAndWithinThePosesOverRandomSequences) {
  const unsigned seed = 421;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.0, 0.25);
  std::uniform_int_distribution<int> shape(0, 2);
  const char* names[] = {"X", "A", "D"};
  for (int family = 0; family < 8; ++family) {
    std::vector<VisemeCue> cues;
    double t = 0;
    for (int i = 0; i < 30; ++i) {
      const double l = length(rng);
      cues.push_back(viseme_cue(t, t + l, names[shape(rng)]));
      t += l;
    }
    CoarticulationOptions o;
    o.frame_rate_hz = 1000;
    const VisemeMotion m = blend_visemes(cues, viseme_test_table(), o, t + 0.2);
    // |dF/dt| <= (pose span) x (spread of d log D / dt) / 2 <= span / tau: per 1 ms sample at most span x 0.001 / 0.05.
    const double bound[2] = {20 * 0.001 / 0.05, 10 * 0.001 / 0.05};
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t k = 0; k < m.times.size(); ++k) {
        ASSERT_GE(m.values[c][k], 0.0) << "seed " << seed << " family " << family;
        ASSERT_LE(m.values[c][k], c == 0 ? 20.0 : 10.0) << "seed " << seed << " family " << family;
        if (k > 0) {
          ASSERT_LE(std::abs(m.values[c][k] - m.values[c][k - 1]), bound[c] * (1 + 1e-9))
              << "seed " << seed << " family " << family << " channel " << c << " at " << m.times[k] << " s";
        }
      }
  }
}

TEST(VisemeBlend, UnknownShapeAndNoCuesAreRefused) {
  const std::vector<VisemeCue> cues = {viseme_cue(0, 0.1, "Q")};
  EXPECT_THROW((void)blend_visemes_at(cues, viseme_test_table(), CoarticulationOptions{}, 0), std::invalid_argument);
  EXPECT_THROW((void)blend_visemes_at({}, viseme_test_table(), CoarticulationOptions{}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace avar::playback
