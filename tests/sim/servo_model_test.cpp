#include "avar/sim/servo_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace avar::sim {
namespace {

TEST(ServoModel, DefaultsAreAStandardHobbyServo) {
  const ServoParams p;
  EXPECT_DOUBLE_EQ(p.max_speed_us_per_s, 2200);
  EXPECT_DOUBLE_EQ(p.time_constant_s, 0.03);
  EXPECT_DOUBLE_EQ(p.deadband_us, 2);
}

TEST(ServoModel, FirstOrderLagTowardThePulse) {
  ServoModel s({1e9, 0.05, 0}, 1000);
  s.step(0.05, 2000);  // one time constant: 63 % of the way
  EXPECT_NEAR(s.position_us(), 1000 + 1000 * (1 - std::exp(-1.0)), 1e-9);
}

TEST(ServoModel, LagIsExactForAnySplitOfTime) {
  ServoModel once({1e9, 0.03, 0}, 1000);
  ServoModel split({1e9, 0.03, 0}, 1000);
  once.step(0.1, 2000);
  for (int i = 0; i < 100; ++i) split.step(0.001, 2000);
  EXPECT_NEAR(once.position_us(), split.position_us(), 1e-9);
}

TEST(ServoModel, TopSpeedCapsTheMotion) {
  ServoModel s({1000, 0.001, 0}, 1000);
  s.step(0.1, 2000);
  EXPECT_NEAR(s.position_us(), 1100, 1e-9);
}

TEST(ServoModel, NoLagMeansOnlyTheTopSpeed) {
  ServoModel s({2200, 0, 0}, 1000);
  s.step(0.1, 2000);
  EXPECT_NEAR(s.position_us(), 1220, 1e-9);
  s.step(1.0, 2000);
  EXPECT_DOUBLE_EQ(s.position_us(), 2000);
}

TEST(ServoModel, DeadbandNoPulseAndNoTime) {
  ServoModel s({1000, 0.01, 3}, 1500);
  s.step(0.1, 1502);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);  // inside the deadband
  s.step(0.1, 1497);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);
  s.step(0.1, 0);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);  // no pulse: stays
  s.step(0.1, std::numeric_limits<double>::quiet_NaN());
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);
  s.step(0, 2000);
  s.step(-1, 2000);
  EXPECT_DOUBLE_EQ(s.position_us(), 1500);
}

TEST(ServoModel, ApproachesWithoutOvershootAndSettlesInsideTheDeadband) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pulse(900, 2100);
  std::uniform_real_distribution<double> speed(500, 6000);
  std::uniform_real_distribution<double> lag(0, 0.1);
  std::uniform_real_distribution<double> band(0, 5);
  std::uniform_real_distribution<double> dt(0.0001, 0.03);
  for (int trial = 0; trial < 200; ++trial) {
    const ServoParams p{speed(rng), lag(rng), band(rng)};
    ServoModel s(p, pulse(rng));
    const double target = pulse(rng);
    double t = 0;
    while (t < 5) {
      const double before = s.position_us();
      const double h = dt(rng);
      s.step(h, target);
      t += h;
      const double after = s.position_us();
      // Never faster than the top speed, never past the pulse, never away from it.
      ASSERT_LE(std::abs(after - before), p.max_speed_us_per_s * h + 1e-9) << "trial " << trial;
      ASSERT_LE(std::abs(target - after), std::abs(target - before) + 1e-9) << "trial " << trial;
      ASSERT_GE((target - before) * (target - after), -1e-9) << "trial " << trial;
    }
    // 5 s is over 40 time constants and longer than any full-range move at the slowest speed.
    EXPECT_LE(std::abs(target - s.position_us()), p.deadband_us + 1e-6) << "trial " << trial;
  }
}

}  // namespace
}  // namespace avar::sim
