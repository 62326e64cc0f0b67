#include "avar/firmware_iface/linear_calibration.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace avar::firmware_iface {
namespace {

LinearCalibration jaw() { return {0, 30, 1200, 1650, false, 0}; }

TEST(LinearCalibration, MapsChannelEndsToPulseEnds) {
  const LinearCalibration c = jaw();
  EXPECT_DOUBLE_EQ(c.to_device(0), 1200);
  EXPECT_DOUBLE_EQ(c.to_device(30), 1650);
  EXPECT_DOUBLE_EQ(c.to_device(15), 1425);
  EXPECT_DOUBLE_EQ(c.device_per_unit(), 15);
}

TEST(LinearCalibration, ReverseSwapsTheEnds) {
  LinearCalibration c = jaw();
  c.reverse = true;
  EXPECT_DOUBLE_EQ(c.to_device(0), 1650);
  EXPECT_DOUBLE_EQ(c.to_device(30), 1200);
  EXPECT_DOUBLE_EQ(c.to_device(10), 1500);
}

TEST(LinearCalibration, TrimShiftsPulsesAndTheWindow) {
  LinearCalibration c = jaw();
  c.trim = 20;
  EXPECT_DOUBLE_EQ(c.to_device(0), 1220);
  EXPECT_DOUBLE_EQ(c.device_low(), 1220);
  EXPECT_DOUBLE_EQ(c.device_high(), 1670);
}

TEST(LinearCalibration, SaturatesOutsideTheWindowAndSaysSo) {
  const LinearCalibration c = jaw();
  bool clamped = false;
  EXPECT_DOUBLE_EQ(c.to_device(45, &clamped), 1650);
  EXPECT_TRUE(clamped);
  EXPECT_DOUBLE_EQ(c.to_device(-1e300, &clamped), 1200);
  EXPECT_TRUE(clamped);
  EXPECT_DOUBLE_EQ(c.to_device(std::numeric_limits<double>::quiet_NaN(), &clamped), 1425);
  EXPECT_TRUE(clamped);
  c.to_device(10, &clamped);
  EXPECT_FALSE(clamped);
}

TEST(LinearCalibration, InverseRoundTripsOverRandomCalibrations) {
  const unsigned seed = 7;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 1000; ++i) {
    LinearCalibration c{-50 * u(rng), 1 + 100 * u(rng), 800 + 500 * u(rng), 1500 + 700 * u(rng), u(rng) < 0.5, -30 + 60 * u(rng)};
    const double v = c.channel_min + u(rng) * (c.channel_max - c.channel_min);
    const double us = c.to_device(v);
    EXPECT_GE(us, c.device_low());
    EXPECT_LE(us, c.device_high());
    EXPECT_NEAR(c.to_channel(us), v, 1e-9);
  }
}

}  // namespace
}  // namespace avar::firmware_iface
