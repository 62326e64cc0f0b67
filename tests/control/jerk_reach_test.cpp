#include "jerk_reach.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "jerk_taylor.hpp"
#include "jerk_test_family.hpp"

namespace avar::control::jerk {
namespace {

TEST(JerkReach, IsTheChangeAndTheStopFromItsPeak) {
  testing::JerkFamily family(20261207);
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, vp] = family.draw();
    const Bounds k(l);
    const Reach r = reach(s.v, s.a, vp, k);
    const VelocityChange c = velocity_change(s.v, s.a, vp, k);
    const double m = stop_peak(vp, k);
    const double stop_duration = m / l.jerk + (m > 0 ? std::abs(vp) / m : 0.0);
    ASSERT_EQ(r.change.distance, c.distance);
    ASSERT_DOUBLE_EQ(r.stop_peak, m);
    ASSERT_NEAR(r.distance, c.distance + 0.5 * vp * stop_duration, 1e-12 * r.magnitude + 1e-300) << "n " << n;
    ASSERT_NEAR(r.duration, c.rise + c.hold + c.fall + stop_duration, 1e-12 * r.duration) << "n " << n;
  }
}

TEST(JerkReach, SlopeCurvatureAndThirdMatchFiniteDifferencesOfTheDistance) {
  testing::JerkFamily family(20261208);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, vp] = family.draw();
    const Bounds k(l);
    const Reach r = reach(s.v, s.a, vp, k);
    const double m = std::min(r.change.hold > 0 ? l.acceleration : r.change.peak, r.stop_peak);
    const double h = 1e-4 * m * m / l.jerk;
    if (!(m > 0) || !stays_inside(r, vp, 2 * h, k)) continue;
    ++checked;
    const auto distance = [&](double x) { return reach(s.v, s.a, x, k).distance; };
    const auto slope = [&](double x) { return reach(s.v, s.a, x, k).slope; };
    const auto curvature = [&](double x) { return reach_curvature(reach(s.v, s.a, x, k), x, k); };
    const double d2 = reach_curvature(r, vp, k), d3 = reach_third(r, vp, k);
    ASSERT_NEAR(r.slope, testing::central_difference(distance, vp, h), 1e-6 * std::abs(r.slope) + 1e-8 * r.magnitude / h)
        << "n " << n;
    ASSERT_NEAR(d2, testing::central_difference(slope, vp, h), 1e-5 * std::abs(d2) + 1e-8 * std::abs(r.slope) / h) << "n " << n;
    ASSERT_NEAR(d3, testing::central_difference(curvature, vp, h), 1e-4 * std::abs(d3) + 1e-8 * std::abs(d2) / h) << "n " << n;
  }
  EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace avar::control::jerk
