#include "jerk_start_models.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "jerk_test_family.hpp"

namespace avar::control::jerk {
namespace {

TEST(JerkStartModels, FromRestTheModelIsTheRoot) {
  testing::JerkFamily family(20261212);
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const Bounds k(l);
    const double d = family.sign() * family.log_uniform(1e-6, 100);
    const Branches b(0, 0, l.velocity, k);
    Reach at_zero = reach(0, 0, 0, k);
    at_zero.distance -= d;
    const double vp = model_from(b, 0, at_zero, true, l, k);
    const Reach r = reach(0, 0, vp, k);
    if (std::abs(vp) < l.velocity) {
      ASSERT_NEAR(r.distance, d, 1e-9 * (std::abs(d) + r.magnitude)) << "n " << n;
    } else {
      ASSERT_LE(std::abs(r.distance), std::abs(d)) << "n " << n;  // the cruise fills the rest
    }
  }
}

TEST(JerkStartModels, BrakingAndCornerModelsLandNearerTheRootThanTheirBranchEnd) {
  testing::JerkFamily family(20261213);
  int braking = 0, corner = 0;
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const MotionState s = family.start(l);
    const Bounds k(l);
    const Branches b(s.v, s.a, l.velocity, k);
    if (b.natural == 0) continue;
    // A root a little beyond the branch end: the braking model checks its own range; the
    // corner's slope is D's first order in u = sqrt(|vp - natural|), whose second order is
    // D' u² (D' ~ |vp|/A + A/J): u up to 1% of where they are equal.
    const double end = family.uniform(0, 1) < 0.5 ? 0.0 : b.natural;
    const double away = end == 0 ? family.sign() : (b.natural > 0 ? 1.0 : -1.0);
    const double u = 1e-2 * family.log_uniform(1e-3, 1) * std::abs(b.corner_slope) /
                     (std::abs(b.natural) / l.acceleration + l.acceleration / l.jerk);
    const double offset = end == 0 ? family.log_uniform(1e-6, 1e-2) * l.velocity : u * u;
    const double root = std::clamp(end + away * offset, -l.velocity, l.velocity);
    const double d = reach(s.v, s.a, root, k).distance;
    Reach at_end = reach(s.v, s.a, end, k);
    at_end.distance -= d;
    const double model = end == 0 ? braking_model(b, at_end, k) : model_from(b, end, at_end, true, l, k);
    if (!(model == model) || (end != 0 && !b.corner_beyond)) continue;
    (end == 0 ? braking : corner) += 1;
    const double at_model = reach(s.v, s.a, model, k).distance - d;
    ASSERT_LE(std::abs(at_model), 0.5 * std::abs(at_end.distance) + 1e-9 * at_end.magnitude) << "n " << n << " end " << end;
  }
  EXPECT_GT(braking, 1000);
  EXPECT_GT(corner, 1000);
}

}  // namespace
}  // namespace avar::control::jerk
