#include "jerk_taylor.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "jerk_test_family.hpp"

namespace avar::control::jerk {
namespace {

TEST(JerkTaylor, NewtonAndSecondOrderStepsAreLeftWithTheResidualsTheyPredict) {
  testing::JerkFamily family(20261209);
  int newton_checked = 0, second_checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, vp] = family.draw();
    const Bounds k(l);
    // A goal whose root is a small step from vp.
    const Reach at = reach(s.v, s.a, vp, k);
    const double m = std::min(at.change.peak, at.stop_peak);
    const double target = vp + family.sign() * family.log_uniform(1e-5, 1e-3) * m * m / l.jerk;
    const double d = reach(s.v, s.a, target, k).distance;
    Reach r = at;
    r.distance -= d;
    const auto residual_at = [&](double x) { return reach(s.v, s.a, x, k).distance - d; };
    const double rounding = 64 * DBL_EPSILON * (r.magnitude + std::abs(d));
    const double step = -r.distance / r.slope;
    const double newton = newton_residual(r, vp, step, k);
    if (newton == newton) {
      ++newton_checked;
      // Left out: D''' step³/6 and beyond (D'' may nearly cancel between the phases).
      const double second_order = 0.5 * std::abs(reach_curvature(r, vp, k)) * step * step;
      const double third_order = std::abs(reach_third(r, vp, k) * step * step * step) / 6;
      ASSERT_NEAR(residual_at(vp + step), newton, 0.02 * second_order + 2 * third_order + rounding) << "n " << n;
    }
    const SecondOrderStep second = second_order_step(r, vp, k);
    if (second.step == second.step) {
      ++second_checked;
      const double x = second.step;
      const double slop = 0.05 * std::abs(second.residual) + 1e-4 * std::abs(reach_curvature(r, vp, k)) * x * x;
      ASSERT_NEAR(residual_at(vp + x), second.residual, slop + rounding) << "n " << n;
    }
  }
  EXPECT_GT(newton_checked, 5000);
  EXPECT_GT(second_checked, 5000);
}

TEST(JerkTaylor, AStepAcrossARegimeIsNotEstimated) {
  const JerkLimits l{10, 100, 1000};
  const Bounds k(l);
  // From rest to vp = 5 neither phase reaches A (J vp = 5000 < A² = 10⁴): a small step stays
  // inside, one that moves the peaks' squares by more than 1% does not.
  const Reach r = reach(0, 0, 5, k);
  EXPECT_TRUE(stays_inside(r, 5, 1e-4, k));
  EXPECT_FALSE(stays_inside(r, 5, 5, k));
  EXPECT_TRUE(std::isnan(newton_residual(r, 5, 5, k)));
  // A step that reverses the stop's velocity.
  EXPECT_FALSE(stays_inside(r, 5, -6, k));
}

}  // namespace
}  // namespace avar::control::jerk
