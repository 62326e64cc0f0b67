#include "avar/playback/curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "avar/playback/bezier_time_solve.hpp"

namespace avar::playback {
namespace {

RawKey key(double t, double v, Interpolation i = Interpolation::linear, std::optional<Handle> left = {},
           std::optional<Handle> right = {}) {
  RawKey k;
  k.time = t;
  k.value = v;
  k.interpolation = i;
  k.left = left;
  k.right = right;
  k.where = {"test.yaml", static_cast<int>(t * 10) + 1, 5};
  return k;
}

Curve build(std::vector<RawKey> keys) { return Curve::build(RawCurve{std::move(keys), {"test.yaml", 1, 1}}); }

TEST(Curve, LinearHitsKeysAndInterpolatesBetween) {
  const Curve c = build({key(0, 0), key(1, 10), key(3, -10)});
  EXPECT_DOUBLE_EQ(c.evaluate(0), 0);
  EXPECT_DOUBLE_EQ(c.evaluate(1), 10);
  EXPECT_DOUBLE_EQ(c.evaluate(3), -10);
  EXPECT_DOUBLE_EQ(c.evaluate(0.25), 2.5);
  EXPECT_DOUBLE_EQ(c.evaluate(2), 0);
}

TEST(Curve, StepHoldsUntilTheNextKey) {
  const Curve c = build({key(0, 1, Interpolation::step), key(1, 5, Interpolation::step), key(2, 9)});
  EXPECT_DOUBLE_EQ(c.evaluate(0.999), 1);
  EXPECT_DOUBLE_EQ(c.evaluate(1), 5);
  EXPECT_DOUBLE_EQ(c.evaluate(1.5), 5);
  EXPECT_DOUBLE_EQ(c.evaluate(2), 9);
}

TEST(Curve, ConstantExtrapolationOutsideTheKeys) {
  const Curve c = build({key(1, 3), key(2, 7)});
  EXPECT_DOUBLE_EQ(c.evaluate(-100), 3);
  EXPECT_DOUBLE_EQ(c.evaluate(0.5), 3);
  EXPECT_DOUBLE_EQ(c.evaluate(2.5), 7);
  EXPECT_DOUBLE_EQ(c.evaluate(1e9), 7);
  const Curve one = build({key(0.5, 4)});
  EXPECT_DOUBLE_EQ(one.evaluate(0), 4);
  EXPECT_DOUBLE_EQ(one.evaluate(9), 4);
}

TEST(Curve, SymmetricBezierSCurvePassesThroughItsMidpoint) {
  // Flat handles at a third of the segment: an ease-in/ease-out S from 0 to 10 over 1 s.
  const Curve c = build({key(0, 0, Interpolation::bezier, {}, Handle{1.0 / 3, 0}), key(1, 10, Interpolation::linear, Handle{2.0 / 3, 10})});
  EXPECT_NEAR(c.evaluate(0.5), 5.0, 1e-12);
  EXPECT_NEAR(c.evaluate(0.25) + c.evaluate(0.75), 10.0, 1e-9);  // point symmetry
  EXPECT_LT(c.evaluate(0.05), 0.1);                              // eases in
  EXPECT_GT(c.evaluate(0.95), 9.9);                              // eases out
}

TEST(Curve, BezierWithHandlesOnTheChordIsLinear) {
  const Curve c = build({key(0, 0, Interpolation::bezier, {}, Handle{1, 3}), key(3, 9, Interpolation::linear, Handle{2, 6})});
  for (double t = 0; t <= 3; t += 0.1) EXPECT_NEAR(c.evaluate(t), 3 * t, 1e-9) << t;
}

TEST(Curve, FlatBezierShortcut) {
  const Curve c = build({key(0, 4, Interpolation::bezier, {}, Handle{0.5, 4}), key(1, 4, Interpolation::linear, Handle{0.5, 4})});
  EXPECT_DOUBLE_EQ(c.evaluate(0.3), 4);
}

TEST(Curve, HandlesLongerThanTheSegmentAreShortenedAsBlenderDoes) {
  // The right handle reaches 2 s into a 1 s segment: Blender scales it by 1/2 (time and value
  // together), i.e. to (1, 5). The curve equals the one authored with that handle.
  const Curve too_long = build({key(0, 0, Interpolation::bezier, {}, Handle{2, 10}), key(1, 0, Interpolation::linear, Handle{0.75, 0})});
  const Curve corrected = build({key(0, 0, Interpolation::bezier, {}, Handle{1, 5}), key(1, 0, Interpolation::linear, Handle{0.75, 0})});
  for (double t = 0; t <= 1.0; t += 0.01) EXPECT_NEAR(too_long.evaluate(t), corrected.evaluate(t), 1e-12) << t;
  // Time never runs backwards: the time cubic of the corrected segment is monotone here.
  const double q[4] = {0, 1, 0.75, 1};
  double last = -1;
  for (double u = 0; u <= 1; u += 0.001) {
    const double tu = bezier_value(q, u);
    EXPECT_GE(tu, last - 1e-12);
    last = tu;
  }
}

TEST(BezierTimeSolve, FindsTheParameterOfATime) {
  const double q[4] = {0, 0.2, 0.9, 1.0};
  for (double u = 0; u <= 1.0; u += 0.05) {
    const double t = bezier_value(q, u);
    EXPECT_NEAR(bezier_parameter_at_time(t, q), u, 1e-7) << u;
  }
  double roots[3];
  EXPECT_EQ(solve_cubic_in_unit_interval(-0.5, 1, 0, 0, roots), 1);  // linear: u = 0.5
  EXPECT_DOUBLE_EQ(roots[0], 0.5);
  EXPECT_EQ(solve_cubic_in_unit_interval(-0.25, 0, 1, 0, roots), 1);  // quadratic: u = 0.5
  EXPECT_DOUBLE_EQ(roots[0], 0.5);
  EXPECT_EQ(solve_cubic_in_unit_interval(1, 0, 0, 0, roots), 0);       // no root
}

TEST(Curve, RejectsBadKeysAtTheirLocation) {
  auto message = [](std::vector<RawKey> keys) -> std::string {
    try {
      build(std::move(keys));
      return "";
    } catch (const InputError& e) {
      return e.what();
    }
  };
  EXPECT_EQ(message({}), "test.yaml:1:1: a track needs at least one key");
  EXPECT_EQ(message({key(0, 0), key(1, 1), key(1, 2)}),
            "test.yaml:11:5: key time 1 s is not after the previous key's 1 s; key times must strictly increase");
  EXPECT_EQ(message({key(0, 0), key(0.5, NAN)}), "test.yaml:6:5: key value nan is not a finite number");
  EXPECT_EQ(message({key(0, 0, Interpolation::bezier), key(1, 1, Interpolation::linear, Handle{0.5, 1})}),
            "test.yaml:1:5: the key at 0 s starts a bezier segment and needs a right handle: right: [time, value]");
  EXPECT_EQ(message({key(0, 0, Interpolation::bezier, {}, Handle{0.5, 0}), key(1, 1)}),
            "test.yaml:11:5: the key at 1 s ends a bezier segment and needs a left handle: left: [time, value]");
}

// Sequential sampling with a cursor agrees with random access everywhere, including backward
// jumps and times outside the keys, and never yields a NaN.
TEST(Curve, CursorAndRandomAccessAgreeOverRandomCurves) {
  const unsigned seed = 1234;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int family = 0; family < 100; ++family) {
    std::vector<RawKey> keys;
    double t = u(rng);
    const int n = 1 + static_cast<int>(rng() % 30);
    for (int i = 0; i < n; ++i) {
      const double v = -100 + 200 * u(rng);
      const auto interp = static_cast<Interpolation>(rng() % 3);
      const double reach = 0.05 + 1.5 * u(rng);  // sometimes longer than the segment
      keys.push_back(key(t, v, interp, Handle{t - reach, v - 50 + 100 * u(rng)}, Handle{t + reach, v - 50 + 100 * u(rng)}));
      t += 0.01 + 2 * u(rng);
    }
    const Curve c = build(keys);
    CurveCursor cursor;
    for (int s = 0; s < 2000; ++s) {
      const double at = s % 97 == 0 ? -5 + (t + 10) * u(rng) : -1 + (t + 2) * s / 2000.0;
      const double seq = c.evaluate(at, cursor);
      ASSERT_TRUE(std::isfinite(seq)) << at;
      ASSERT_EQ(seq, c.evaluate(at)) << at;
    }
    for (const RawKey& k : keys) ASSERT_NEAR(c.evaluate(k.time), k.value, 1e-9);
  }
}

// Linear and Bezier interpolation are continuous: no jump between close samples.
TEST(Curve, LinearAndBezierAreContinuous) {
  const unsigned seed = 99;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int family = 0; family < 50; ++family) {
    std::vector<RawKey> keys;
    double t = 0;
    for (int i = 0; i < 10; ++i) {
      const double v = -10 + 20 * u(rng);
      const auto interp = rng() % 2 ? Interpolation::bezier : Interpolation::linear;
      keys.push_back(key(t, v, interp, Handle{t - 0.3 * u(rng), v + u(rng)}, Handle{t + 0.3 * u(rng), v - u(rng)}));
      t += 0.2 + u(rng);
    }
    const Curve c = build(keys);
    const double h = 1e-7;
    for (double x = 0; x < t; x += 0.0137) ASSERT_NEAR(c.evaluate(x), c.evaluate(x + h), 1e-3) << x;
  }
}

}  // namespace
}  // namespace avar::playback
