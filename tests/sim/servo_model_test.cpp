#include "avar/sim/servo_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace avar::sim {
namespace {

TEST(ServoModel, FirstOrderLagTowardThePulse) {
  ServoModel s({1e9, 0.05, 0}, 1000);
  s.step(0.05, 2000);  // one time constant: 63 % of the way
  EXPECT_NEAR(s.position_us(), 1000 + 1000 * (1 - std::exp(-1.0)), 1e-9);
}

TEST(ServoModel, TopSpeedCapsTheMotion) {
  ServoModel s({1000, 0.001, 0}, 1000);
  s.step(0.1, 2000);
  EXPECT_NEAR(s.position_us(), 1100, 1e-9);
}

TEST(ServoModel, DeadbandAndNoPulse) {
  ServoModel s({1000, 0.01, 3}, 1500);
  s.step(0.1, 1502);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);  // inside the deadband
  s.step(0.1, 0);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);  // no pulse: stays
}

}  // namespace
}  // namespace avar::sim
