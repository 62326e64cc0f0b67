#include "jerk_velocity_change.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "jerk_reach.hpp"
#include "jerk_taylor.hpp"
#include "jerk_test_family.hpp"

namespace avar::control::jerk {
namespace {

TEST(JerkVelocityChange, EndsAtItsVelocityAtRestWithinTheLimitsAndCoversItsDistance) {
  testing::JerkFamily family(20261202);
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, v1] = family.draw();
    const Bounds k(l);
    const VelocityChange c = velocity_change(s.v, s.a, v1, k);
    ASSERT_LE(c.peak, l.acceleration);
    ASSERT_GE(c.rise, 0);
    ASSERT_GE(c.hold, 0);
    ASSERT_GE(c.fall, 0);
    // Integrated piece by piece: jerk sJ, 0, -sJ.
    const MotionState end = testing::run_pieces({0, s.v, s.a}, {{c.rise, c.s * l.jerk}, {c.hold, 0}, {c.fall, -c.s * l.jerk}});
    const double duration = c.rise + c.hold + c.fall;
    ASSERT_NEAR(end.a, 0, 1e-9 * l.acceleration) << "n " << n;
    ASSERT_NEAR(end.v, v1, 1e-9 * (std::abs(s.v) + l.acceleration * duration)) << "n " << n;
    ASSERT_NEAR(end.p, c.distance, 1e-9 * c.magnitude + 1e-300) << "n " << n;
  }
}

TEST(JerkVelocityChange, SlopeCurvatureAndThirdMatchFiniteDifferences) {
  testing::JerkFamily family(20261203);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, vp] = family.draw();
    const Bounds k(l);
    const VelocityChange c = velocity_change(s.v, s.a, vp, k);
    const bool holds = c.hold > 0;
    const double m = holds ? l.acceleration : c.peak;
    const double h = 1e-4 * m * m / l.jerk;
    // Only well inside the change's regime (stays_inside guards the stop's as well).
    if (!(c.peak > 0) || !stays_inside(reach(s.v, s.a, vp, k), vp, 2 * h, k)) continue;
    ++checked;
    const auto distance = [&](double x) { return velocity_change(s.v, s.a, x, k).distance; };
    const auto slope = [&](double x) {
      const VelocityChange at = velocity_change(s.v, s.a, x, k);
      return change_slope(at.s, x, at.peak, k);
    };
    const auto curvature = [&](double x) {
      const VelocityChange at = velocity_change(s.v, s.a, x, k);
      return change_curvature(at.s, x, at.peak, at.hold > 0, k);
    };
    const double d1 = change_slope(c.s, vp, c.peak, k), d2 = change_curvature(c.s, vp, c.peak, holds, k);
    const double d3 = change_third(c.s, vp, c.peak, holds, k);
    const double fd1 = testing::central_difference(distance, vp, h);
    const double fd2 = testing::central_difference(slope, vp, h);
    const double fd3 = testing::central_difference(curvature, vp, h);
    ASSERT_NEAR(d1, fd1, 1e-6 * std::abs(d1) + 1e-8 * c.magnitude / h) << "n " << n;
    ASSERT_NEAR(d2, fd2, 1e-5 * std::abs(d2) + 1e-8 * std::abs(d1) / h) << "n " << n;
    ASSERT_NEAR(d3, fd3, 1e-4 * std::abs(d3) + 1e-8 * std::abs(d2) / h) << "n " << n;
  }
  EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace avar::control::jerk
