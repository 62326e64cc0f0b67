#include "avar/control/ramp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace avar::control {
namespace {

TEST(Ramp, StartsAndEndsExactlyWithZeroSpeed) {
  Ramp ramp(2);
  ramp.plan(std::vector<double>{0, 10}, std::vector<double>{30, 10}, std::vector<double>{15, 15}, 0.1);
  // The 30-unit move at a peak of 15 units/s takes pi*30/(2*15) = pi seconds.
  EXPECT_NEAR(ramp.duration(), std::numbers::pi, 1e-12);
  std::vector<double> a(2), b(2);
  ramp.sample(0, a);
  EXPECT_DOUBLE_EQ(a[0], 0);
  ramp.sample(ramp.duration(), a);
  EXPECT_DOUBLE_EQ(a[0], 30);
  EXPECT_DOUBLE_EQ(a[1], 10);
  ramp.sample(1e-4, b);
  EXPECT_LT(b[0], 1e-5);  // eases in: almost no motion in the first 0.1 ms
}

TEST(Ramp, PeakSpeedNeverExceedsTheChannelsRampVelocity) {
  Ramp ramp(3);
  const std::vector<double> peak{20, 5, 100};
  ramp.plan(std::vector<double>{0, 0, 0}, std::vector<double>{40, -7, 3}, peak, 0.25);
  std::vector<double> prev(3), now(3);
  ramp.sample(0, prev);
  const double dt = 1e-3;
  for (double t = dt; t <= ramp.duration() + dt; t += dt) {
    ramp.sample(t, now);
    for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(now[i] - prev[i]) / dt, peak[i] * (1 + 1e-6));
    prev = now;
  }
}

TEST(Ramp, ShortMovesStillTakeTheMinimumDuration) {
  Ramp ramp(1);
  ramp.plan(std::vector<double>{0}, std::vector<double>{0.001}, std::vector<double>{100}, 0.25);
  EXPECT_DOUBLE_EQ(ramp.duration(), 0.25);
}

}  // namespace
}  // namespace avar::control
