#include "avar/firmware_iface/device_watch.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace avar::firmware_iface {
namespace {

TEST(DeviceWatch, IsLostOnTheSilentTickThatReachesTheBudget) {
  DeviceWatch watch(3);
  EXPECT_FALSE(watch.lost());
  EXPECT_FALSE(watch.missed());
  EXPECT_FALSE(watch.missed());
  EXPECT_TRUE(watch.missed());  // the third in a row
  EXPECT_TRUE(watch.lost());
  EXPECT_EQ(watch.silent_ticks(), 3u);
  EXPECT_TRUE(watch.missed());  // and stays lost while silent
  EXPECT_EQ(watch.silent_ticks(), 4u);
}

TEST(DeviceWatch, AnAnswerEmptiesTheCountAndEndsTheLoss) {
  DeviceWatch watch(3);
  watch.missed();
  watch.missed();
  watch.answered();  // one short of the budget: a later silence gets all of it again
  EXPECT_EQ(watch.silent_ticks(), 0u);
  EXPECT_FALSE(watch.missed());
  EXPECT_FALSE(watch.missed());
  EXPECT_TRUE(watch.missed());
  watch.answered();
  EXPECT_FALSE(watch.lost());
  EXPECT_EQ(watch.silent_ticks(), 0u);
}

TEST(DeviceWatch, ABudgetOfOneTickIsLostOnTheFirstSilentTickAndZeroIsTakenAsOne) {
  DeviceWatch one(1);
  EXPECT_FALSE(one.lost());
  EXPECT_TRUE(one.missed());
  DeviceWatch zero(0);
  EXPECT_EQ(zero.budget(), 1u);
  EXPECT_FALSE(zero.lost());  // not lost before any silence
  EXPECT_TRUE(zero.missed());
  EXPECT_EQ(DeviceWatch().budget(), 1u);
}

TEST(DeviceWatch, TheCountSaturates) {
  DeviceWatch watch(std::numeric_limits<std::uint32_t>::max());
  for (int i = 0; i < 5; ++i) watch.missed();
  EXPECT_FALSE(watch.lost());
  EXPECT_EQ(watch.silent_ticks(), 5u);
}

TEST(SilenceBudget, IsTheFewestWholeTicksThatLastTheWatchdogTime) {
  EXPECT_EQ(silence_budget(0.100, 100), 10u);
  EXPECT_EQ(silence_budget(0.250, 50), 13u);  // 12.5 ticks: 13 last at least 250 ms
  EXPECT_EQ(silence_budget(0.300, 100), 30u);
  EXPECT_EQ(silence_budget(0.101, 100), 11u);
  EXPECT_EQ(silence_budget(60.0, 1000), 60000u);
}

TEST(SilenceBudget, IgnoresTheRoundingErrorOfTheProduct) {
  // 0.07 * 100 is 7.000000000000001 in binary floating point; 0.035 * 200 likewise.
  EXPECT_EQ(silence_budget(0.070, 100), 7u);
  EXPECT_EQ(silence_budget(0.035, 200), 7u);
  EXPECT_EQ(silence_budget(0.068, 750), 51u);
}

TEST(SilenceBudget, IsNeverBelowTwoTicks) {
  EXPECT_EQ(kMinSilenceBudget, 2u);
  EXPECT_EQ(silence_budget(0.001, 100), 2u);  // a tenth of a tick
  EXPECT_EQ(silence_budget(0.010, 100), 2u);  // one tick
  EXPECT_EQ(silence_budget(0.020, 100), 2u);
  EXPECT_EQ(silence_budget(0.021, 100), 3u);
  EXPECT_EQ(silence_budget(0, 100), 2u);
  EXPECT_EQ(silence_budget(-1, 100), 2u);
  EXPECT_EQ(silence_budget(std::numeric_limits<double>::quiet_NaN(), 100), 2u);
}

TEST(SilenceBudget, SaturatesBeyondTheCounter) {
  EXPECT_EQ(silence_budget(1e12, 1000), std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(silence_budget(std::numeric_limits<double>::infinity(), 100), std::numeric_limits<std::uint32_t>::max());
}

}  // namespace
}  // namespace avar::firmware_iface
