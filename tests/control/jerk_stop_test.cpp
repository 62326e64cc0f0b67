#include "jerk_stop.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "avar/control/jerk_profile.hpp"
#include "jerk_test_family.hpp"
#include "jerk_velocity_change.hpp"

namespace avar::control::jerk {
namespace {

/// The stop from (vp, 0) as reach() takes it: distance vp T/2 over T = m/J + |vp|/m.
double stop_distance(double vp, const Bounds& k) {
  const double m = stop_peak(vp, k);
  return 0.5 * vp * (m * k.inv_J + stop_coast(std::abs(vp), m, m >= k.A, k));
}

TEST(JerkStop, TheStopFromThePeakReachesRestAfterItsDistance) {
  testing::JerkFamily family(20261204);
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const Bounds k(l);
    const double vp = family.uniform(-l.velocity, l.velocity);
    const double m = stop_peak(vp, k);
    ASSERT_LE(m, l.acceleration);
    const double ramp = m / l.jerk, hold = m > 0 ? std::max(0.0, std::abs(vp) / m - m / l.jerk) : 0.0;
    const double jerk = vp > 0 ? -l.jerk : l.jerk;
    const MotionState end = testing::run_pieces({0, vp, 0}, {{ramp, jerk}, {hold, 0}, {ramp, -jerk}});
    ASSERT_NEAR(end.a, 0, 1e-12 * l.acceleration) << "n " << n;
    ASSERT_NEAR(end.v, 0, 1e-9 * std::abs(vp)) << "n " << n;
    ASSERT_NEAR(end.p, stop_distance(vp, k), 1e-9 * std::abs(end.p)) << "n " << n;
  }
}

TEST(JerkStop, BrakingFromAnyStateReachesRestAtTheStoppingPoint) {
  testing::JerkFamily family(20261205);
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const MotionState s = family.start(l);
    const VelocityChange brake = velocity_change(s.v, s.a, 0, Bounds(l));
    const MotionState end =
        testing::run_pieces(s, {{brake.rise, brake.s * l.jerk}, {brake.hold, 0}, {brake.fall, -brake.s * l.jerk}});
    ASSERT_NEAR(end.a, 0, 1e-9 * l.acceleration) << "n " << n;
    ASSERT_NEAR(end.v, 0, 1e-9 * (std::abs(s.v) + l.velocity)) << "n " << n;
    ASSERT_NEAR(end.p, stopping_point(s, l), 1e-9 * (std::abs(s.p) + brake.magnitude)) << "n " << n;
  }
}

TEST(JerkStop, SlopeCurvatureAndThirdMatchFiniteDifferences) {
  testing::JerkFamily family(20261206);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const Bounds k(l);
    const double vp = family.uniform(-l.velocity, l.velocity);
    const double m = stop_peak(vp, k);
    const double h = 1e-4 * m * m / l.jerk;
    // Well inside the stop's regime: its peak squared moves by 0.01% and stays off A.
    if (!(m > 0) || std::abs(m * m - l.acceleration * l.acceleration) < 0.01 * m * m) continue;
    ++checked;
    const auto slope = [&](double x) {
      const double mx = stop_peak(x, k);
      return stop_slope(stop_coast(std::abs(x), mx, mx >= k.A, k), mx, k);
    };
    const auto curvature = [&](double x) { return stop_curvature(x, stop_peak(x, k), k); };
    const auto distance = [&](double x) { return stop_distance(x, k); };
    const double d1 = slope(vp), d2 = curvature(vp), d3 = stop_third(m, k);
    ASSERT_NEAR(d1, testing::central_difference(distance, vp, h), 1e-6 * std::abs(d1) + 1e-8 * std::abs(distance(vp)) / h)
        << "n " << n;
    ASSERT_NEAR(d2, testing::central_difference(slope, vp, h), 1e-5 * std::abs(d2) + 1e-8 * std::abs(d1) / h) << "n " << n;
    ASSERT_NEAR(d3, testing::central_difference(curvature, vp, h), 1e-4 * std::abs(d3) + 1e-8 * std::abs(d2) / h) << "n " << n;
  }
  EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace avar::control::jerk
