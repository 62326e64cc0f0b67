// Fitting samples with Bezier keys: the built curve stays within the tolerance at every sample
// on seeded random smooth and noisy data, with far fewer keys than samples; handles keep time
// monotone; steps and corners are kept as keys with broken tangents.
#include "avar/playback/offline/curve_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace avar::playback {
namespace {

struct Samples {
  std::vector<double> t, v;
};

/// A smooth random motion: a few sines, over `seconds` at `rate` Hz (jittered times if asked).
Samples smooth_motion(std::mt19937& rng, double seconds, double rate, bool jitter) {
  std::uniform_real_distribution<double> freq(0.1, 1.5), amp(1, 10), phase(0, 6.28), jit(-0.3, 0.3);
  double f[3], a[3], p[3];
  for (int i = 0; i < 3; ++i) f[i] = freq(rng), a[i] = amp(rng), p[i] = phase(rng);
  Samples s;
  const auto n = static_cast<std::size_t>(seconds * rate) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = (static_cast<double>(i) + (jitter && i > 0 && i + 1 < n ? jit(rng) : 0.0)) / rate;
    double v = 0;
    for (int k = 0; k < 3; ++k) v += a[k] * std::sin(2 * M_PI * f[k] * t + p[k]);
    s.t.push_back(t);
    s.v.push_back(v);
  }
  return s;
}

/// Every sample within the tolerance of the built curve; handles inside their segments.
void expect_within(const Samples& s, const CurveFitResult& fit, double tolerance, unsigned seed) {
  const Curve curve = Curve::build(fit.curve);
  double worst = 0;
  for (std::size_t i = 0; i < s.t.size(); ++i) worst = std::max(worst, std::abs(curve.evaluate(s.t[i]) - s.v[i]));
  EXPECT_LE(worst, tolerance) << "seed " << seed;
  EXPECT_NEAR(worst, fit.max_error, 1e-12) << "seed " << seed;
  const auto& keys = fit.curve.keys;
  EXPECT_EQ(keys.front().time, s.t.front());
  EXPECT_EQ(keys.front().value, s.v.front());
  EXPECT_EQ(keys.back().time, s.t.back());
  EXPECT_EQ(keys.back().value, s.v.back());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    ASSERT_EQ(keys[k].interpolation, Interpolation::bezier);
    if (k + 1 < keys.size()) {
      ASSERT_GT(keys[k].right->time, keys[k].time) << "seed " << seed;
      ASSERT_LT(keys[k + 1].left->time, keys[k + 1].time) << "seed " << seed;
      ASSERT_LE(keys[k].right->time, keys[k + 1].left->time + 1e-12) << "seed " << seed;
    }
  }
}

TEST(CurveFit, SmoothRandomDataWithinToleranceWithFewKeys) {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed);
    const Samples s = smooth_motion(rng, 6, 100, seed % 2 == 0);
    const double tolerance = 0.1;
    const CurveFitResult fit = fit_curve(s.t, s.v, {.tolerance = tolerance});
    expect_within(s, fit, tolerance, seed);
    EXPECT_LT(fit.curve.keys.size() * 5, s.t.size()) << "seed " << seed << ": " << fit.curve.keys.size() << " keys";
    EXPECT_TRUE(fit.corners.empty()) << "seed " << seed;
  }
}

TEST(CurveFit, NoisyRecordingWithinToleranceWithFewKeys) {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed);
    Samples s = smooth_motion(rng, 6, 120, false);
    std::normal_distribution<double> noise(0, 0.1);
    for (double& v : s.v) v += noise(rng);
    const double tolerance = 0.5;  // 5 sigma of the noise
    const CurveFitResult fit = fit_curve(s.t, s.v, {.tolerance = tolerance});
    expect_within(s, fit, tolerance, seed);
    EXPECT_LT(fit.curve.keys.size() * 5, s.t.size()) << "seed " << seed << ": " << fit.curve.keys.size() << " keys";
    EXPECT_TRUE(fit.corners.empty()) << "seed " << seed;
  }
}

TEST(CurveFit, StepIsKeptAsTwoCornerKeys) {
  Samples s;
  for (int i = 0; i <= 200; ++i) {
    s.t.push_back(i / 100.0);
    s.v.push_back(i <= 100 ? 0.0 : 10.0);
  }
  const CurveFitResult fit = fit_curve(s.t, s.v, {.tolerance = 0.01});
  expect_within(s, fit, 0.01, 0);
  EXPECT_EQ(fit.corners, (std::vector<std::size_t>{100, 101}));
  EXPECT_EQ(fit.key_samples, (std::vector<std::size_t>{0, 100, 101, 200}));
  const Curve curve = Curve::build(fit.curve);
  for (double t : {0.0, 0.5, 0.999, 1.0}) EXPECT_NEAR(curve.evaluate(t), 0.0, 0.01) << t;
  for (double t : {1.01, 1.5, 2.0}) EXPECT_NEAR(curve.evaluate(t), 10.0, 0.01) << t;
}

TEST(CurveFit, VCornerIsKeptWithBrokenTangents) {
  Samples s;
  for (int i = 0; i <= 200; ++i) {
    s.t.push_back(i / 100.0);
    s.v.push_back(std::abs(s.t.back() - 1.0));
  }
  const CurveFitResult fit = fit_curve(s.t, s.v, {.tolerance = 0.001});
  expect_within(s, fit, 0.001, 0);
  EXPECT_EQ(fit.key_samples, (std::vector<std::size_t>{0, 100, 200}));
  EXPECT_LT(fit.max_error, 1e-9);
  EXPECT_NEAR(fit.curve.keys[1].left->value, 1.0 / 3.0 * 1.0, 1e-9);  // slope -1 arriving
  EXPECT_NEAR(fit.curve.keys[1].right->value, 1.0 / 3.0 * 1.0, 1e-9);  // slope +1 leaving
  // Without corner detection it still fits, with more keys.
  const CurveFitResult smooth = fit_curve(s.t, s.v, {.tolerance = 0.001, .keep_corners = false});
  expect_within(s, smooth, 0.001, 0);
  EXPECT_GT(smooth.curve.keys.size(), 3u);
}

TEST(CurveFit, OneSampleOneKeyAndBadInputRefused) {
  const std::vector<double> t = {0.5}, v = {2.0};
  const CurveFitResult fit = fit_curve(t, v, {.tolerance = 0.1});
  ASSERT_EQ(fit.curve.keys.size(), 1u);
  EXPECT_EQ(Curve::build(fit.curve).evaluate(3.0), 2.0);
  const std::vector<double> two = {0, 1}, back = {1, 0}, nan = {0, NAN};
  EXPECT_THROW(fit_curve(two, v, {.tolerance = 0.1}), std::invalid_argument);
  EXPECT_THROW(fit_curve(back, two, {.tolerance = 0.1}), std::invalid_argument);
  EXPECT_THROW(fit_curve(two, nan, {.tolerance = 0.1}), std::invalid_argument);
  EXPECT_THROW(fit_curve(two, two, {.tolerance = 0}), std::invalid_argument);
  EXPECT_THROW(fit_curve(std::vector<double>{}, std::vector<double>{}, {.tolerance = 1}), std::invalid_argument);
}

TEST(CurveFit, StraightLineNeedsOnlyItsEnds) {
  Samples s;
  for (int i = 0; i <= 1000; ++i) s.t.push_back(i * 0.01), s.v.push_back(3 - 2 * s.t.back());
  const CurveFitResult fit = fit_curve(s.t, s.v, {.tolerance = 1e-6});
  EXPECT_EQ(fit.curve.keys.size(), 2u);
  expect_within(s, fit, 1e-6, 0);
}

}  // namespace
}  // namespace avar::playback
