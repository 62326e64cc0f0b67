#include "avar/firmware_iface/pulse_calibration.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace avar::firmware_iface {
namespace {

PulseCalibration jaw() { return {0, 30, 1200, 1650, false, 0}; }

TEST(PulseCalibration, MapsChannelEndsToPulseEnds) {
  const PulseCalibration c = jaw();
  EXPECT_DOUBLE_EQ(c.to_pulse_us(0), 1200);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(30), 1650);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(15), 1425);
  EXPECT_DOUBLE_EQ(c.us_per_unit(), 15);
}

TEST(PulseCalibration, ReverseSwapsTheEnds) {
  PulseCalibration c = jaw();
  c.reverse = true;
  EXPECT_DOUBLE_EQ(c.to_pulse_us(0), 1650);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(30), 1200);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(10), 1500);
}

TEST(PulseCalibration, TrimShiftsPulsesAndTheWindow) {
  PulseCalibration c = jaw();
  c.trim_us = 20;
  EXPECT_DOUBLE_EQ(c.to_pulse_us(0), 1220);
  EXPECT_DOUBLE_EQ(c.pulse_low_us(), 1220);
  EXPECT_DOUBLE_EQ(c.pulse_high_us(), 1670);
}

TEST(PulseCalibration, SaturatesOutsideTheWindowAndSaysSo) {
  const PulseCalibration c = jaw();
  bool clamped = false;
  EXPECT_DOUBLE_EQ(c.to_pulse_us(45, &clamped), 1650);
  EXPECT_TRUE(clamped);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(-1e300, &clamped), 1200);
  EXPECT_TRUE(clamped);
  EXPECT_DOUBLE_EQ(c.to_pulse_us(std::numeric_limits<double>::quiet_NaN(), &clamped), 1425);
  EXPECT_TRUE(clamped);
  c.to_pulse_us(10, &clamped);
  EXPECT_FALSE(clamped);
}

TEST(PulseCalibration, InverseRoundTripsOverRandomCalibrations) {
  const unsigned seed = 7;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 1000; ++i) {
    PulseCalibration c{-50 * u(rng), 1 + 100 * u(rng), 800 + 500 * u(rng), 1500 + 700 * u(rng), u(rng) < 0.5, -30 + 60 * u(rng)};
    const double v = c.channel_min + u(rng) * (c.channel_max - c.channel_min);
    const double us = c.to_pulse_us(v);
    EXPECT_GE(us, c.pulse_low_us());
    EXPECT_LE(us, c.pulse_high_us());
    EXPECT_NEAR(c.to_channel(us), v, 1e-9);
  }
}

}  // namespace
}  // namespace avar::firmware_iface
