// Properties over seeded random curves: sequential sampling with a cursor equals random access
// bit for bit (forward, backward and far jumps, outside the keys), every key is hit, nothing is
// ever NaN, and linear and Bezier segments are continuous.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::build;
using testing::key;

/// A random curve of n keys with every interpolation and every kind of handle.
std::vector<RawKey> random_keys(std::mt19937& rng, int n, bool continuous_only = false) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<RawKey> keys;
  double t = -3 + 6 * u(rng);
  for (int i = 0; i < n; ++i) {
    const double v = -100 + 200 * u(rng);
    const auto interp = continuous_only ? (rng() % 2 ? Interpolation::bezier : Interpolation::linear)
                                        : static_cast<Interpolation>(rng() % 3);
    const auto reach = [&] { return continuous_only ? 0.02 + 0.5 * u(rng) : -0.3 + 2.0 * u(rng); };
    const double left = reach(), right = reach();
    keys.push_back(key(t, v, interp, Handle{t - left, v - 50 + 100 * u(rng)}, Handle{t + right, v - 50 + 100 * u(rng)}));
    t += (continuous_only ? 0.05 : 0.001) + 2 * u(rng);
  }
  return keys;
}

TEST(CurveProperty, CursorAndRandomAccessAgreeBitForBit) {
  const unsigned seed = 1234;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int family = 0; family < 200; ++family) {
    const std::vector<RawKey> keys = random_keys(rng, 1 + static_cast<int>(rng() % 40));
    const Curve c = build(keys);
    const double start = keys.front().time, end = keys.back().time, span = end - start + 2;
    CurveCursor cursor;
    double t = start - 1;
    for (int s = 0; s < 3000; ++s) {
      switch (rng() % 10) {
        case 0: t = start - 1 + span * u(rng); break;                    // jump anywhere, often backwards
        case 1: t -= 0.5 * u(rng); break;                                // small step back
        case 2: t = keys[rng() % keys.size()].time; break;               // exactly on a key
        case 3: t += 3 * u(rng); break;                                  // several segments ahead
        default: t += 0.001 + 0.01 * u(rng); break;                      // a tick forward
      }
      if (t > end + 1) t = start - 1;
      const double sequential = c.evaluate(t, cursor);
      ASSERT_TRUE(std::isfinite(sequential)) << "family " << family << " t " << t;
      ASSERT_EQ(sequential, c.evaluate(t)) << "family " << family << " t " << t;
      // Warming reads what comes next from wherever the cursor is, and changes nothing.
      ASSERT_TRUE(std::isfinite(c.warm(cursor)));
    }
    for (double odd : {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                       std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::max()}) {
      ASSERT_TRUE(std::isfinite(c.evaluate(odd, cursor)));
      ASSERT_EQ(c.evaluate(odd, cursor), c.evaluate(odd));
    }
  }
}

// Keys on the frames of a scene (k / fps, as Blender's exporter writes them), with every Blender
// interpolation: at a key's time, rounded to the nanosecond or off by up to 0.9 us either way, a
// curve returns the key's value, by random access and from a cursor a tick before.
TEST(CurveProperty, AtAKeysTimeOnAnyRoundingTheKeysValue) {
  const unsigned seed = 4242;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double rates[] = {24, 25, 30, 60, 120, 24000.0 / 1001, 30000.0 / 1001};
  for (int family = 0; family < 300; ++family) {
    const double fps = rates[rng() % std::size(rates)];
    std::vector<RawKey> keys;
    long frame = static_cast<long>(rng() % 200) - 100;
    for (int i = 0, n = 2 + static_cast<int>(rng() % 20); i < n; ++i) {
      const double t = static_cast<double>(frame) / fps, v = -100 + 200 * u(rng);
      const auto interp = static_cast<Interpolation>(rng() % (static_cast<unsigned>(Interpolation::elastic) + 1));
      keys.push_back(
          key(t, v, interp, Handle{t - 0.3 * u(rng), v - 50 + 100 * u(rng)}, Handle{t + 0.3 * u(rng), v - 50 + 100 * u(rng)}));
      frame += 1 + static_cast<long>(rng() % 40);
    }
    RawCurve raw = testing::raw_curve(keys);
    raw.extrapolation = rng() % 2 ? Extrapolation::linear : Extrapolation::constant;
    const Curve c = Curve::build(raw);
    for (const RawKey& k : keys) {
      for (const double t : {k.time, std::round(k.time * 1e9) / 1e9, std::nextafter(k.time, -1e9), std::nextafter(k.time, 1e9),
                             k.time - 0.9 * Curve::kKeySnap, k.time + 0.9 * Curve::kKeySnap}) {
        ASSERT_NEAR(c.evaluate(t), k.value, 1e-9 * (1 + std::abs(k.value)))
            << "family " << family << " fps " << fps << " " << to_string(k.interpolation) << " key at " << k.time
            << " s, sampled at " << t << " s";
        CurveCursor cursor;
        c.evaluate(t - 1.0 / fps, cursor);
        ASSERT_EQ(c.evaluate(t, cursor), c.evaluate(t))
            << "family " << family << " key at " << k.time << " s, sampled at " << t << " s";
      }
    }
  }
}

TEST(CurveProperty, ACursorFromAnotherCurveOrAStaleOneIsHarmless) {
  const unsigned seed = 5;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  const Curve big = build(random_keys(rng, 50));
  const Curve small = build(random_keys(rng, 3));
  CurveCursor cursor;
  big.evaluate(big.end_time() - 0.001, cursor);  // cursor now far beyond small's segments
  EXPECT_TRUE(std::isfinite(small.warm(cursor)));
  EXPECT_EQ(Curve{}.warm(cursor), 0.0);
  for (double t = small.start_time() - 1; t < small.end_time() + 1; t += 0.01) ASSERT_EQ(small.evaluate(t, cursor), small.evaluate(t));
  cursor.segment = static_cast<std::size_t>(-1);
  EXPECT_TRUE(std::isfinite(big.warm(cursor)));
  ASSERT_EQ(big.evaluate(big.start_time() + 0.5, cursor), big.evaluate(big.start_time() + 0.5));
}

TEST(CurveProperty, EveryKeyIsHitExactly) {
  const unsigned seed = 42;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int family = 0; family < 200; ++family) {
    const std::vector<RawKey> keys = random_keys(rng, 2 + static_cast<int>(rng() % 20));
    const Curve c = build(keys);
    CurveCursor cursor;
    for (const RawKey& k : keys) {
      ASSERT_EQ(c.evaluate(k.time), k.value) << "family " << family << " key at " << k.time;
      ASSERT_EQ(c.evaluate(k.time, cursor), k.value);
    }
  }
}

TEST(CurveProperty, LinearAndBezierAreContinuous) {
  const unsigned seed = 99;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int family = 0; family < 100; ++family) {
    const std::vector<RawKey> keys = random_keys(rng, 10, true);
    const Curve c = build(keys);
    // Segments of at least 0.05 s, handles at most 0.52 s long and values within 150 of their key
    // bound the slope to about 10^4 per second.
    for (const RawKey& k : keys)
      for (double h : {1e-7, 1e-9}) ASSERT_NEAR(c.evaluate(k.time - h), c.evaluate(k.time + h), 2e-2) << k.time;
    for (double x = keys.front().time; x < keys.back().time; x += 0.0137) ASSERT_NEAR(c.evaluate(x), c.evaluate(x + 1e-8), 1e-3) << x;
  }
}

}  // namespace
}  // namespace avar::playback
