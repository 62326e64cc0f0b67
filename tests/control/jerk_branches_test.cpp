#include "jerk_branches.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "jerk_reach.hpp"
#include "jerk_test_family.hpp"

namespace avar::control::jerk {
namespace {

TEST(JerkBranches, TheNaturalVelocityReleasesTheAccelerationAndIsZeroWhenBrakingOntoRest) {
  const JerkLimits l{10, 100, 1000};
  const Bounds k(l);
  const Branches rising(1, 20, l.velocity, k);
  EXPECT_DOUBLE_EQ(rising.natural, 1 + 0.5 * 20 * 20 / 1000.0);
  EXPECT_EQ(rising.low, 0);
  EXPECT_EQ(rising.high, rising.natural);
  EXPECT_TRUE(!rising.corner_beyond);
  const Branches turning(1, -20, l.velocity, k);
  EXPECT_DOUBLE_EQ(turning.natural, 1 - 0.2);
  EXPECT_TRUE(turning.corner_beyond);
  EXPECT_DOUBLE_EQ(turning.corner_slope, 2 * turning.natural / std::sqrt(1000.0));
  // v = -a|a|/(2J), to rounding: the natural velocity is 0.
  const Branches braking(0.2 * (1 + 2 * DBL_EPSILON), -20, l.velocity, k);
  EXPECT_EQ(braking.natural, 0);
  EXPECT_EQ(braking.low, braking.high);
}

TEST(JerkBranches, TheDistanceIncreasesBeyondBothBranchEnds) {
  testing::JerkFamily family(20261210);
  for (int n = 0; n < 2000; ++n) {
    const JerkLimits l = family.limits();
    const MotionState s = family.start(l);
    const Bounds k(l);
    const Branches b(s.v, s.a, l.velocity, k);
    double above = reach(s.v, s.a, b.high, k).distance, below = reach(s.v, s.a, b.low, k).distance;
    for (int i = 1; i <= 50; ++i) {
      const double f = i / 50.0;
      const Reach up = reach(s.v, s.a, b.high + f * (l.velocity - b.high), k);
      const Reach down = reach(s.v, s.a, b.low - f * (l.velocity + b.low), k);
      ASSERT_GE(up.distance, above - 1e-12 * up.magnitude) << "n " << n << " i " << i;
      ASSERT_LE(down.distance, below + 1e-12 * down.magnitude) << "n " << n << " i " << i;
      above = up.distance, below = down.distance;
    }
  }
}

TEST(JerkBranches, TheCornerMapRoundTripsAndItsSlopeIsTheChainRule) {
  testing::JerkFamily family(20261211);
  for (int n = 0; n < 2000; ++n) {
    const double natural = family.uniform(-10, 10), dir = family.sign();
    const CornerMap map{true, natural, dir};
    const double x = natural + dir * family.uniform(1e-3, 5);
    const double u = map.to_u(x);
    ASSERT_NEAR(map.to_vp(u), x, 1e-14 * (std::abs(natural) + std::abs(x)));
    // d/du of a linear f(vp) = c vp.
    const double c = family.uniform(0.5, 2);
    const auto f = [&](double w) { return c * map.to_vp(w); };
    ASSERT_NEAR(map.slope(c, u), testing::central_difference(f, u, 1e-5 * u), 1e-6 * std::abs(map.slope(c, u)));
  }
  const CornerMap identity{false, 3, 1};
  EXPECT_EQ(identity.to_u(7), 7);
  EXPECT_EQ(identity.to_vp(7), 7);
  EXPECT_EQ(identity.slope(2, 7), 2);
}

}  // namespace
}  // namespace avar::control::jerk
