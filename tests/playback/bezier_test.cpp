// Bezier segments as Blender evaluates them: handle correction, the root order of the time solve,
// hand-computed shapes, and agreement with Blender's algorithm written out literally.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "avar/playback/runtime/bezier_time_solve.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::build;
using testing::key;

constexpr Interpolation kLinearKey = Interpolation::linear;
constexpr Interpolation kBezierKey = Interpolation::bezier;

std::vector<double> roots_of(double c0, double c1, double c2, double c3) {
  double r[3];
  const int n = solve_cubic_in_unit_interval(c0, c1, c2, c3, r);
  return std::vector<double>(r, r + n);
}

void expect_roots(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-12) << "root " << i;
}

TEST(BezierTimeSolve, ThreeRootsComeLargestThenSmallestThenMiddle) {
  // (u - 0.2)(u - 0.5)(u - 0.9) = u^3 - 1.6 u^2 + 0.73 u - 0.09, and the same scaled by -2.
  expect_roots(roots_of(-0.09, 0.73, -1.6, 1), {0.9, 0.2, 0.5});
  expect_roots(roots_of(0.18, -1.46, 3.2, -2), {0.9, 0.2, 0.5});
  // (u + 0.5)(u - 0.3)(u - 0.8): the smallest root is outside the window, so 0.8 then 0.3.
  expect_roots(roots_of(0.12, -0.31, -0.6, 1), {0.8, 0.3});
}

TEST(BezierTimeSolve, QuadraticsAndLinesInBlendersOrder) {
  // (u - 0.2)(u - 0.7): (-c1 - sqrt D) / 2 c2 first, which is the smaller root when c2 > 0 ...
  expect_roots(roots_of(0.14, -0.9, 1, 0), {0.2, 0.7});
  // ... and the larger one when c2 < 0.
  expect_roots(roots_of(-0.14, 0.9, -1, 0), {0.7, 0.2});
  expect_roots(roots_of(-0.25, 0, 1, 0), {0.5});
  expect_roots(roots_of(-0.5, 1, 0, 0), {0.5});
  expect_roots(roots_of(0, 0, 0, 0), {0});
  expect_roots(roots_of(1, 0, 0, 0), {});
  expect_roots(roots_of(1, 0, 1, 0), {});  // no real root
}

TEST(BezierTimeSolve, AcceptanceWindowIsBlendersInFloat) {
  expect_roots(roots_of(5e-11, 1, 0, 0), {-5e-11});      // >= -1e-10
  expect_roots(roots_of(1e-9, 1, 0, 0), {});             // below -1e-10
  expect_roots(roots_of(-1.0000005, 1, 0, 0), {1.0000005});  // <= 1.000001f
  expect_roots(roots_of(-1.00001, 1, 0, 0), {});
}

TEST(BezierTimeSolve, ARoundingResidueOfTheCubicTermIsNotDividedBy) {
  // x(u) = u (handles at thirds) with a cubic term left by rounding: Blender's formula divides
  // by 1e-17 and loses the root in cancellation; the root is 0.3.
  expect_roots(roots_of(-0.3, 1, 2e-17, 1e-17), {0.3});
  expect_roots(roots_of(-0.3, 1, 0, -3e-16), {0.3});
}

TEST(BezierTimeSolve, FindsTheParameterOfATime) {
  const double q[4] = {2, 2.2, 2.9, 3.0};
  for (double u = 0; u <= 1.0; u += 0.05) EXPECT_NEAR(bezier_parameter_at_time(bezier_value(q, u), q), u, 1e-9) << u;
  EXPECT_LT(bezier_parameter_at_time(3.5, q), 0);
}

TEST(BezierHandleCorrection, EachTooLongHandleIsScaledToTheSegmentLength) {
  // Segment from (0, 0) to (1, 4). Right handle 2 s long: scaled by 1/2. Left handle reaching
  // back 1.5 s: scaled by 2/3, value offset too. Current Blender scales each handle alone; the
  // older rule (both by length / (sum of extents) = 1/3.5) would give other points.
  double time[4] = {0, 2, -0.5, 1};
  double value[4] = {0, 10, 1, 4};
  correct_bezier_handles(time, value);
  EXPECT_DOUBLE_EQ(time[1], 1);
  EXPECT_DOUBLE_EQ(value[1], 5);
  EXPECT_DOUBLE_EQ(time[2], 0);
  EXPECT_DOUBLE_EQ(value[2], 2);
}

TEST(BezierHandleCorrection, HandlesWithinTheSegmentAndBackwardHandlesStay) {
  double time[4] = {0, 0.4, 0.7, 1};
  double value[4] = {0, 3, 2, 4};
  correct_bezier_handles(time, value);
  EXPECT_EQ(time[1], 0.4);
  EXPECT_EQ(time[2], 0.7);
  double back_time[4] = {0, -0.5, 1.5, 1};  // both point the wrong way, each 0.5 s long
  double back_value[4] = {0, 1, 2, 4};
  correct_bezier_handles(back_time, back_value);
  EXPECT_EQ(back_time[1], -0.5);
  EXPECT_EQ(back_time[2], 1.5);
  EXPECT_EQ(back_value[1], 1);
}

TEST(BezierCurve, SymmetricSCurvePassesThroughItsMidpoint) {
  // Flat handles 0.39 of the segment long (Blender's automatic length): an ease-in/ease-out S
  // from 0 to 10 over 2 s, point-symmetric about its middle.
  const Curve c = build({key(1, 0, kBezierKey, {}, Handle{1.78, 0}), key(3, 10, kLinearKey, Handle{2.22, 10})});
  EXPECT_NEAR(c.evaluate(2), 5, 1e-12);
  for (double d = 0.05; d < 1; d += 0.05) EXPECT_NEAR(c.evaluate(2 - d) + c.evaluate(2 + d), 10, 1e-9) << d;
  EXPECT_LT(c.evaluate(1.1), 0.1);
  EXPECT_GT(c.evaluate(2.9), 9.9);
  for (double t = 1; t < 3; t += 0.01) EXPECT_LE(c.evaluate(t), c.evaluate(t + 0.01)) << t;
}

TEST(BezierCurve, HandlesOnTheChordGiveAStraightLine) {
  const Curve c = build({key(0, 0, kBezierKey, {}, Handle{1, 3}), key(3, 9, kLinearKey, Handle{2, 6})});
  for (double t = 0; t <= 3; t += 0.1) EXPECT_NEAR(c.evaluate(t), 3 * t, 1e-9) << t;
}

TEST(BezierCurve, FourEqualValuesGiveBlendersConstantShortcut) {
  const Curve c = build({key(0, 4, kBezierKey, {}, Handle{2, 4}), key(1, 4, kLinearKey, Handle{-3, 4})});
  for (double t = 0; t <= 1; t += 0.1) EXPECT_EQ(c.evaluate(t), 4) << t;
}

TEST(BezierCurve, AHandleThatWouldMakeTimeRunBackwardsIsCorrectedAsBlenderDoes) {
  // The right handle reaches 2 s into a 1 s segment, so uncorrected the time x(u) would pass the
  // end key and come back. Blender scales it by 1/2 (time and value): the curve is the one
  // authored with the handle at (1, 5), and time never runs backwards along it.
  const Curve too_long = build({key(0, 0, kBezierKey, {}, Handle{2, 10}), key(1, 0, kLinearKey, Handle{0.75, 0})});
  const Curve corrected = build({key(0, 0, kBezierKey, {}, Handle{1, 5}), key(1, 0, kLinearKey, Handle{0.75, 0})});
  for (double t = 0; t <= 1.0; t += 0.01) EXPECT_NEAR(too_long.evaluate(t), corrected.evaluate(t), 1e-12) << t;
  const double uncorrected[4] = {0, 2, 0.75, 1}, fixed[4] = {0, 1, 0.75, 1};
  double max_uncorrected = 0;
  for (double u = 0; u <= 1; u += 0.001) {
    max_uncorrected = std::max(max_uncorrected, bezier_value(uncorrected, u));
    EXPECT_GE(bezier_value(fixed, u + 0.001), bezier_value(fixed, u) - 1e-15) << u;
  }
  EXPECT_GT(max_uncorrected, 1.1);  // the uncorrected time overshoots the end key
}

TEST(BezierCurve, BothHandlesAtFullLengthStillGiveAFunctionOfTime) {
  // Each handle is 5 s long in a 1 s segment and is corrected to reach the other key:
  // x(u) = 3u - 6u^2 + 4u^3 rises with a flat inflection at u = 1/2, where by symmetry the value
  // is the average of the keys. The value rises with time everywhere (its control values do).
  const Curve c = build({key(0, -2, kBezierKey, {}, Handle{5, 8}), key(1, 6, kLinearKey, Handle{-4, -4})});
  EXPECT_NEAR(c.evaluate(0.5), 2, 1e-6);
  for (double t = 0; t < 1; t += 0.001) {
    ASSERT_TRUE(std::isfinite(c.evaluate(t)));
    EXPECT_GE(c.evaluate(t + 0.001), c.evaluate(t) - 1e-9) << t;
  }
}

TEST(BezierCurve, BackwardRightHandleTakesBlendersRoot) {
  // Right handle 0.5 s BEFORE its key: x(u) = -1.5u + 5.1u^2 - 2.6u^3 first runs backwards, so a
  // time just after the key has three roots: about -t/1.5, 0.36 and 1.6. Blender tries the
  // largest (outside), then the smallest: while it lies within [-1e-10, 0] the value stays at the
  // key; a little later it falls outside and the middle root, far along the segment, takes over.
  const Curve c = build({key(0, 0, kBezierKey, {}, Handle{-0.5, 50}), key(1, 10, kLinearKey, Handle{0.7, 10})});
  // Within the key snap the time is the key's: its value, as Blender's own threshold has it.
  EXPECT_NEAR(c.evaluate(1e-12), 0, 1e-9);
  EXPECT_EQ(c.evaluate(1e-9), 0);
  // Past the snap the smallest root (about -t/1.5) is outside: the middle root, from its limit
  // for x -> 0 refined by Newton's method at this t.
  const double t = 2 * Curve::kKeySnap;
  double u = (5.1 - std::sqrt(5.1 * 5.1 - 4 * 2.6 * 1.5)) / 5.2;
  for (int i = 0; i < 20; ++i) u -= (-1.5 * u + 5.1 * u * u - 2.6 * u * u * u - t) / (-1.5 + 10.2 * u - 7.8 * u * u);
  const double f[4] = {0, 50, 10, 10};
  EXPECT_NEAR(c.evaluate(t), bezier_value(f, u), 1e-6);
  EXPECT_GT(c.evaluate(t), 20);
}

// Blender's evaluation of one F-curve, written out as fcurve.cc has it (in double): constant
// extrapolation, a key's own value on the key, per-handle correction, solve_cubic with the sum of
// two cube roots, the first root in its window, berekeny. Returns NaN where Blender finds no
// root (it would return 0).
double blender_reference(const std::vector<RawKey>& keys, double t) {
  // Blender's binary search takes a time within its threshold of a key as the key (0.0001
  // frame); in seconds, avar's key snap.
  for (const RawKey& k : keys)
    if (std::abs(t - k.time) <= Curve::kKeySnap) t = k.time;
  if (t <= keys.front().time) return keys.front().value;
  if (t >= keys.back().time) return keys.back().value;
  std::size_t i = 0;
  while (keys[i + 1].time <= t) ++i;
  const RawKey &a = keys[i], &b = keys[i + 1];
  if (t == a.time) return a.value;
  if (a.interpolation == Interpolation::step) return a.value;
  if (a.interpolation == Interpolation::linear) return (b.value - a.value) * (t - a.time) / (b.time - a.time) + a.value;
  double v1[2] = {a.time, a.value}, v2[2] = {a.right->time, a.right->value};
  double v3[2] = {b.left->time, b.left->value}, v4[2] = {b.time, b.value};
  if (std::abs(v1[1] - v4[1]) < 1.1920929e-7 && std::abs(v2[1] - v3[1]) < 1.1920929e-7 && std::abs(v3[1] - v4[1]) < 1.1920929e-7)
    return v1[1];
  const double h1[2] = {v1[0] - v2[0], v1[1] - v2[1]}, h2[2] = {v4[0] - v3[0], v4[1] - v3[1]};
  const double len = v4[0] - v1[0], len1 = std::abs(h1[0]), len2 = std::abs(h2[0]);
  if (len1 + len2 != 0) {
    if (len1 > len) v2[0] = v1[0] - len / len1 * h1[0], v2[1] = v1[1] - len / len1 * h1[1];
    if (len2 > len) v3[0] = v4[0] - len / len2 * h2[0], v3[1] = v4[1] - len / len2 * h2[1];
  }
  const double c0 = v1[0] - t, c1 = 3 * (v2[0] - v1[0]), c2 = 3 * (v1[0] - 2 * v2[0] + v3[0]),
               c3 = v4[0] - v1[0] + 3 * (v2[0] - v3[0]);
  const auto ok = [](double r) { return static_cast<float>(r) >= static_cast<float>(-1e-10) && static_cast<float>(r) <= 1.000001f; };
  std::vector<double> candidates;
  if (c3 != 0) {
    double A = c2 / c3 / 3;
    const double B = c1 / c3, C = c0 / c3;
    const double p = B / 3 - A * A, q = (2 * A * A * A - A * B + C) / 2, d = q * q + p * p * p;
    if (d > 0) {
      candidates = {std::cbrt(-q + std::sqrt(d)) + std::cbrt(-q - std::sqrt(d)) - A};
    } else if (d == 0) {
      candidates = {2 * std::cbrt(-q) - A, -std::cbrt(-q) - A};
    } else {
      const double phi = std::acos(-q / std::sqrt(-(p * p * p))), s = std::sqrt(-p), cp = std::cos(phi / 3);
      const double sq = std::sqrt(3 - 3 * cp * cp);
      candidates = {2 * s * cp - A, -s * (cp + sq) - A, -s * (cp - sq) - A};
    }
  } else if (c2 != 0) {
    const double D = c1 * c1 - 4 * c2 * c0;
    if (D > 0) candidates = {(-c1 - std::sqrt(D)) / (2 * c2), (-c1 + std::sqrt(D)) / (2 * c2)};
    if (D == 0) candidates = {-c1 / (2 * c2)};
  } else if (c1 != 0) {
    candidates = {-c0 / c1};
  }
  for (double u : candidates)
    if (ok(u))
      return v1[1] + u * 3 * (v2[1] - v1[1]) + u * u * 3 * (v1[1] - 2 * v2[1] + v3[1]) + u * u * u * (v4[1] - v1[1] + 3 * (v2[1] - v3[1]));
  return std::nan("");
}

// Random Bezier curves of every kind of handle (short, long, too long, backwards, zero length,
// steep values) agree with Blender's algorithm at random times and at times near the keys.
TEST(BezierCurve, AgreesWithBlendersAlgorithmOverRandomCurves) {
  const unsigned seed = 20240611;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int compared = 0, no_root = 0;
  for (int family = 0; family < 300; ++family) {
    std::vector<RawKey> keys;
    double t = -5 + 10 * u(rng);
    for (int i = 0; i < 12; ++i) {
      const double v = -90 + 180 * u(rng);
      const auto reach = [&] {
        switch (rng() % 5) {
          case 0: return 0.0;                   // zero-length handle
          case 1: return -0.5 * u(rng);         // pointing the wrong way
          case 2: return 0.5 + 2.5 * u(rng);    // longer than the segment, often
          default: return 0.05 + 0.6 * u(rng);  // ordinary
        }
      };
      const double left = reach(), right = reach();
      keys.push_back(key(t, v, kBezierKey, Handle{t - left, v + 200 * (u(rng) - 0.5) * left},
                         Handle{t + right, v + 200 * (u(rng) - 0.5) * right}));
      t += 0.05 + 2 * u(rng);
    }
    const Curve c = build(keys);
    std::vector<double> times;
    for (int k = 0; k < 400; ++k) times.push_back(keys.front().time - 0.5 + (keys.back().time - keys.front().time + 1) * u(rng));
    for (const RawKey& k : keys)
      for (double dt : {0.0, 1e-9, 1e-6, 1e-3, -1e-9, -1e-6, -1e-3}) times.push_back(k.time + dt);
    for (double x : times) {
      const double want = blender_reference(keys, x);
      if (std::isnan(want)) {
        ++no_root;
        continue;
      }
      ++compared;
      ASSERT_NEAR(c.evaluate(x), want, 1e-6 * (1 + std::abs(want))) << "family " << family << " t " << x;
    }
  }
  EXPECT_GT(compared, 100000);
  EXPECT_LT(no_root, compared / 1000);
}

// Curves whose handles keep time increasing use the tabulated inverse; it must agree with
// Blender's closed form to far better than Blender's own float rounding.
TEST(BezierCurve, TabulatedInverseMatchesTheClosedForm) {
  const unsigned seed = 77;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0;
  for (int family = 0; family < 500; ++family) {
    const double t0 = 100 * u(rng), d = 0.01 + 5 * u(rng);
    const double a = u(rng), b = u(rng);  // handle extents as fractions of the segment
    const double v0 = -50 + 100 * u(rng), v1 = -50 + 100 * u(rng), h0 = -50 + 100 * u(rng), h1 = -50 + 100 * u(rng);
    const Curve c = build({key(t0, v0, kBezierKey, {}, Handle{t0 + a * d, h0}), key(t0 + d, v1, kLinearKey, Handle{t0 + d - b * d, h1})});
    const double times[4] = {t0, t0 + a * d, t0 + d - b * d, t0 + d};
    const double values[4] = {v0, h0, h1, v1};
    for (int k = 0; k < 200; ++k) {
      const double x = t0 + d * u(rng);
      const double param = bezier_parameter_at_time(x, times);
      ASSERT_GE(param, -1e-10);
      const double err = std::abs(c.evaluate(x) - bezier_value(values, param));
      worst = std::max(worst, err);
      ASSERT_LT(err, 1e-6) << "family " << family << " t " << x;
    }
  }
  RecordProperty("worst_error", std::to_string(worst));
}

}  // namespace
}  // namespace avar::playback
