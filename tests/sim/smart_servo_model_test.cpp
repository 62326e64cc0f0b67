#include "avar/sim/smart_servo_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "avar/sim/servo_model.hpp"

namespace avar::sim {
namespace {

/// A servo without lag, so that only its speed and acceleration caps shape the motion.
SmartServoParams brisk_servo() {
  SmartServoParams p;
  p.max_speed = 1000;
  p.max_acceleration = 10'000;
  p.time_constant_s = 0;
  p.heating_c_per_s_at_full_load = 10;
  p.cooling_per_s = 0.1;
  return p;
}

TEST(SmartServoModel, FollowsTheGoalWithTheSameLagAsTheHobbyServo) {
  SmartServoParams p;
  p.max_speed = 1e9;
  p.max_acceleration = 1e12;
  p.time_constant_s = 0.05;
  SmartServoModel smart(p, 1000);
  ServoModel hobby({1e9, 0.05, 0}, 1000);
  for (int i = 0; i < 50; ++i) {
    smart.advance(0.001, true, 2000);
    hobby.step(0.001, 2000);
  }
  EXPECT_NEAR(smart.position(), hobby.position_us(), 1.0);
  EXPECT_NEAR(smart.position(), 1000 + 1000 * (1 - std::exp(-1.0)), 1.0);
}

TEST(SmartServoModel, SpeedAndAccelerationAreCappedByTheMotorAndTheRegisters) {
  SmartServoModel free_run(brisk_servo(), 0);
  free_run.advance(0.05, true, 10'000);  // 0.1 s to top speed: still accelerating
  EXPECT_NEAR(free_run.velocity(), 500, 1e-6);
  free_run.advance(0.5, true, 10'000);
  EXPECT_NEAR(free_run.velocity(), 1000, 1e-6);
  SmartServoModel limited(brisk_servo(), 0);
  limited.advance(0.5, true, 10'000, 200, 1000);
  EXPECT_NEAR(limited.velocity(), 200, 1e-6);
  EXPECT_NEAR(limited.position(), 0.5 * 1000 * 0.2 * 0.2 + 200 * 0.3, 1.0);  // ramp 0.2 s, then cruise
}

TEST(SmartServoModel, LoadComesFromAccelerationSpeedAndTheExternalLoad) {
  SmartServoModel s(brisk_servo(), 0);
  s.advance(0.01, true, 10'000);
  EXPECT_NEAR(s.load(), kLoadAtMaxAcceleration + kLoadAtMaxSpeed * s.velocity() / 1000, 1e-9);
  s.advance(1, true, 10'000);  // cruising: speed only
  EXPECT_NEAR(s.load(), kLoadAtMaxSpeed, 1e-9);
  s.set_external_load(-0.9);
  s.set_position(10'000);
  s.advance(0.01, true, 10'000);  // holding still against the arm
  EXPECT_NEAR(s.load(), -0.9, 1e-9);
  s.set_external_load(2);
  s.advance(0.01, true, 10'000);
  EXPECT_EQ(s.load(), 1.0);  // saturates at the rated torque
  s.advance(0.01, false, 0);
  EXPECT_EQ(s.load(), 0.0);  // torque off: limp, nothing held
  EXPECT_EQ(s.velocity(), 0.0);
  EXPECT_EQ(s.position(), 10'000);
}

TEST(SmartServoModel, TemperatureRisesWithLoadAndCoolsTowardAmbient) {
  SmartServoModel s(brisk_servo(), 0);
  s.set_external_load(1);
  s.advance(1, true, 0);
  const double hot = s.temperature_c();
  EXPECT_NEAR(hot, 25 + 10 * (1 - std::exp(-0.1)) / 0.1, 0.05);  // heating 10 °C/s against cooling
  s.advance(30, false, 0);
  EXPECT_LT(s.temperature_c(), hot);
  EXPECT_NEAR(s.temperature_c(), 25 + (hot - 25) * std::exp(-3.0), 0.05);
  s.advance(0, true, 0);  // no time, no change
  s.advance(-1, true, 0);
  EXPECT_NEAR(s.temperature_c(), 25 + (hot - 25) * std::exp(-3.0), 0.05);
}

TEST(SmartServoModel, DeadbandHoldsTheHornStill) {
  SmartServoParams p = brisk_servo();
  p.deadband = 3;
  SmartServoModel s(p, 100);
  s.advance(0.1, true, 102.5);
  EXPECT_EQ(s.position(), 100);
  s.advance(0.1, true, 110);
  EXPECT_NEAR(s.position(), 110, 3);
}

}  // namespace
}  // namespace avar::sim
