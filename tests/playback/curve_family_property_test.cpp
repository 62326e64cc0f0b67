// Properties of every interpolation family over seeded random curves: C1 where the family
// promises it (Catmull-Rom, cardinal, Kochanek-Bartels with continuity 0, Bezier with auto and
// auto_clamped handles, B-spline, which is also C2 on evenly spaced keys), keys hit exactly by
// the interpolating families, a monotone Bezier time solve, cursor equal to random access also
// through Cycles, and no NaN anywhere, extreme and non-finite times included. Sampling curves of
// every kind allocates nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "avar/playback/runtime/bezier_time_solve.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

constexpr unsigned kSeeds[] = {1u, 7u, 2024u, 99991u};

/// n keys with random values and spacing (or evenly spaced), every key with `interpolation`
/// and random family parameters that keep the family's promise (continuity 0 when `smooth`).
RawCurve family_curve(std::mt19937& rng, Interpolation interpolation, int n, bool smooth, bool even = false) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<RawKey> keys;
  double t = -2 + 4 * u(rng);
  for (int i = 0; i < n; ++i) {
    RawKey k = key(t, -100 + 200 * u(rng), interpolation);
    if (interpolation == Interpolation::cardinal || interpolation == Interpolation::kochanek_bartels) k.tension = -1 + 2 * u(rng);
    if (interpolation == Interpolation::kochanek_bartels) {
      k.bias = -1 + 2 * u(rng);
      k.continuity = smooth ? 0 : -1 + 2 * u(rng);
    }
    if (interpolation == Interpolation::hermite) k.in_slope = -50 + 100 * u(rng), k.out_slope = -50 + 100 * u(rng);
    if (interpolation == Interpolation::back) k.back = 3 * u(rng);
    if (interpolation == Interpolation::elastic) k.amplitude = 300 * u(rng), k.period = u(rng) < 0.5 ? 0.0 : 0.05 + u(rng);
    k.easing = static_cast<Easing>(rng() % 4);
    keys.push_back(k);
    t += even ? 0.5 : 0.2 + 2 * u(rng);
  }
  return raw_curve(std::move(keys));
}

// One-sided first and second derivatives with second-order differences.
double slope_after(const Curve& c, double t, double h) { return (-3 * c.evaluate(t) + 4 * c.evaluate(t + h) - c.evaluate(t + 2 * h)) / (2 * h); }
double slope_before(const Curve& c, double t, double h) { return (3 * c.evaluate(t) - 4 * c.evaluate(t - h) + c.evaluate(t - 2 * h)) / (2 * h); }
double curvature_after(const Curve& c, double t, double h) {
  return (2 * c.evaluate(t) - 5 * c.evaluate(t + h) + 4 * c.evaluate(t + 2 * h) - c.evaluate(t + 3 * h)) / (h * h);
}
double curvature_before(const Curve& c, double t, double h) {
  return (2 * c.evaluate(t) - 5 * c.evaluate(t - h) + 4 * c.evaluate(t - 2 * h) - c.evaluate(t - 3 * h)) / (h * h);
}

void expect_c1_at_interior_keys(const RawCurve& raw, const std::string& what) {
  const Curve c = Curve::build(raw);
  for (std::size_t i = 1; i + 1 < raw.keys.size(); ++i) {
    const double t = raw.keys[i].time;
    const double before = slope_before(c, t, 1e-5), after = slope_after(c, t, 1e-5);
    EXPECT_NEAR(before, after, 1e-3 * (1 + std::abs(before))) << what << " at key " << i << " (" << t << " s)";
  }
}

TEST(CurveFamilies, SplinesAreC1WhereTheyPromiseIt) {
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    for (Interpolation i : {Interpolation::catmull_rom, Interpolation::cardinal, Interpolation::kochanek_bartels, Interpolation::bspline})
      expect_c1_at_interior_keys(family_curve(rng, i, 12, true, i == Interpolation::bspline), to_string(i));
  }
}

TEST(CurveFamilies, KochanekBartelsContinuityBreaksTheTangent) {
  RawCurve raw = raw_curve({key(0, 0, Interpolation::kochanek_bartels), key(1, 10, Interpolation::kochanek_bartels),
                            key(2, 0, Interpolation::kochanek_bartels)});
  raw.keys[1].continuity = 0.5;
  raw.keys[1].tension = 0;
  const Curve c = Curve::build(raw);
  // Chords +10 and -10 per second: in = (0.5 * 10 - 1.5 * 10) / 2, out = (1.5 * 10 - 0.5 * 10) / 2.
  EXPECT_NEAR(slope_before(c, 1, 1e-5), -5, 1e-3);
  EXPECT_NEAR(slope_after(c, 1, 1e-5), 5, 1e-3);
}

TEST(CurveFamilies, BSplineIsC2OnEvenlySpacedKeys) {
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    const RawCurve raw = family_curve(rng, Interpolation::bspline, 10, true, true);
    const Curve c = Curve::build(raw);
    for (std::size_t i = 1; i + 1 < raw.keys.size(); ++i) {
      const double t = raw.keys[i].time;
      const double before = curvature_before(c, t, 1e-3), after = curvature_after(c, t, 1e-3);
      EXPECT_NEAR(before, after, 1e-4 * (1 + std::abs(before))) << "key " << i;
    }
    // The approximation starts and ends on the first and last keys.
    EXPECT_NEAR(c.evaluate(raw.keys.front().time), raw.keys.front().value, 1e-9);
    EXPECT_NEAR(c.evaluate(raw.keys.back().time), raw.keys.back().value, 1e-9);
  }
}

TEST(CurveFamilies, AutoHandlesAreC1) {
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    for (HandleType type : {HandleType::automatic, HandleType::auto_clamped})
      for (AutoSmoothing smoothing : {AutoSmoothing::none, AutoSmoothing::continuous_acceleration}) {
        RawCurve raw = family_curve(rng, Interpolation::bezier, 10, true);
        for (RawKey& k : raw.keys) k.left_type = k.right_type = type;
        raw.auto_smoothing = smoothing;
        expect_c1_at_interior_keys(raw, std::string(to_string(type)) + " " + to_string(smoothing));
      }
  }
}

TEST(CurveFamilies, InterpolatingFamiliesHitEveryKey) {
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    for (int f = 0; f < static_cast<int>(Interpolation::bspline); ++f) {
      const auto interpolation = static_cast<Interpolation>(f);
      const RawCurve raw = family_curve(rng, interpolation, 8, false);
      const Curve c = Curve::build(raw);
      CurveCursor cursor;
      for (const RawKey& k : raw.keys) {
        EXPECT_NEAR(c.evaluate(k.time), k.value, 1e-9 * (1 + std::abs(k.value))) << to_string(interpolation) << " at " << k.time;
        EXPECT_EQ(c.evaluate(k.time, cursor), c.evaluate(k.time));
      }
    }
  }
}

TEST(CurveFamilies, BezierTimeSolveIsMonotone) {
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 200; ++trial) {
      // Handles inside the segment: time increases with the parameter, so must the solve.
      const double q[4] = {0.0, u(rng), u(rng), 1.0};
      double previous = -1;
      for (int j = 0; j <= 400; ++j) {
        const double x = j / 400.0;
        const double p = bezier_parameter_at_time(x, q);
        ASSERT_GE(p, previous - 1e-9) << "handles " << q[1] << ", " << q[2] << " at x " << x;
        ASSERT_NEAR(bezier_polynomial(q).at(p), x, 1e-6);
        previous = p;
      }
    }
  }
}

/// Every family, handle type, extrapolation and Cycles mode, with random parameters.
Curve random_everything(std::mt19937& rng) {
  const auto interpolation = static_cast<Interpolation>(rng() % (static_cast<unsigned>(Interpolation::bspline) + 1));
  RawCurve raw = family_curve(rng, interpolation, 1 + static_cast<int>(rng() % 7), false);
  for (RawKey& k : raw.keys) {
    k.interpolation = static_cast<Interpolation>(rng() % (static_cast<unsigned>(Interpolation::bspline) + 1));
    k.in_slope = k.in_slope.value_or(3.0), k.out_slope = k.out_slope.value_or(-3.0);
    k.left_type = static_cast<HandleType>(2 + rng() % 3);
    k.right_type = static_cast<HandleType>(2 + rng() % 3);
  }
  raw.extrapolation = static_cast<Extrapolation>(rng() % 2);
  raw.auto_smoothing = static_cast<AutoSmoothing>(rng() % 2);
  raw.cycles.before = static_cast<CycleMode>(rng() % 4);
  raw.cycles.after = static_cast<CycleMode>(rng() % 4);
  raw.cycles.before_count = static_cast<int>(rng() % 3);
  raw.cycles.after_count = static_cast<int>(rng() % 3);
  return Curve::build(raw);
}

TEST(CurveFamilies, NoNaNAnywhereAndCursorMatchesRandomAccess) {
  const double inf = std::numeric_limits<double>::infinity();
  for (unsigned seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-30, 30);
    for (int trial = 0; trial < 300; ++trial) {
      const Curve c = random_everything(rng);
      CurveCursor cursor;
      for (double t : {-inf, inf, std::numeric_limits<double>::quiet_NaN(), 1e300, -1e300, 1e-310, -1e-310, 0.0})
        EXPECT_TRUE(std::isfinite(c.evaluate(t))) << "trial " << trial << " t " << t;
      for (int j = 0; j < 400; ++j) {
        const double t = j % 50 == 0 ? u(rng) : -30 + j * 0.15;
        const double v = c.evaluate(t, cursor);
        ASSERT_TRUE(std::isfinite(v)) << "trial " << trial << " t " << t;
        ASSERT_EQ(v, c.evaluate(t)) << "trial " << trial << " t " << t;
      }
    }
  }
}

TEST(CurveFamilies, CyclesRepeatOffsetAndMirror) {
  RawCurve raw = raw_curve({key(1, 0), key(2, 10)});
  raw.cycles.after = CycleMode::repeat_offset;
  raw.cycles.before = CycleMode::mirror;
  const Curve c = Curve::build(raw);
  EXPECT_NEAR(c.evaluate(2.5), 15, 1e-12);   // second cycle, raised by the change
  EXPECT_NEAR(c.evaluate(3.25), 22.5, 1e-12);
  EXPECT_NEAR(c.evaluate(0.75), 2.5, 1e-12);  // mirrored: 1 - 0.25 plays 1 + 0.25
  EXPECT_NEAR(c.evaluate(-0.25), 7.5, 1e-12);  // the second cycle before runs forward again
  raw.cycles.after = CycleMode::repeat;
  raw.cycles.after_count = 1;
  raw.extrapolation = Extrapolation::linear;
  const Curve counted = Curve::build(raw);
  EXPECT_NEAR(counted.evaluate(2.5), 5, 1e-12);
  EXPECT_NEAR(counted.evaluate(3.5), 25, 1e-12);  // past the count: Blender extrapolates from the real time
}

TEST(CurveFamilies, LinearExtrapolationFollowsBlendersSlopeRules) {
  RawCurve raw = raw_curve({key(0, 0, Interpolation::linear), key(1, 10, Interpolation::bezier, Handle{0.5, 10}, Handle{1.5, 20}),
                            key(2, 0, Interpolation::step)});
  raw.keys[2].left = Handle{1.5, 0};
  raw.extrapolation = Extrapolation::linear;
  const Curve c = Curve::build(raw);
  EXPECT_NEAR(c.evaluate(-1), -10, 1e-12);  // linear first key: the line to its neighbour
  EXPECT_EQ(c.evaluate(3), 0);              // constant last key: holds
}

}  // namespace
}  // namespace avar::playback
