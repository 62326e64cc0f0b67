#include "avar/control/live_inputs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace avar::control {
namespace {

std::vector<LiveChannel> live_test_channels() { return {{"jaw", 0, 40}, {"neck_pan", -60, 60}}; }

ControlMapping live_test_mapping(std::string control, std::size_t channel, double low, double high) {
  ControlMapping m;
  m.control = std::move(control);
  m.channel = channel;
  m.low = low;
  m.high = high;
  m.crossfade_s = 0;
  return m;
}

TEST(LiveInputs, WithoutAnyMessageTheShowPlaysThrough) {
  LiveInputs live(live_test_channels(), {live_test_mapping("x", 1, -60, 60)});
  std::vector<double> frame{12, 34};
  live.apply(0, frame);
  EXPECT_DOUBLE_EQ(frame[0], 12);
  EXPECT_DOUBLE_EQ(frame[1], 34);
  EXPECT_TRUE(std::isnan(live.control_values()[0]));
}

TEST(LiveInputs, AnAbsoluteMappingSpansTheOutputRangeByTheControlsPolarity) {
  LiveInputs live(live_test_channels(), {live_test_mapping("x", 1, -60, 60), live_test_mapping("fader", 0, 0, 40)});
  live.sink().post("x", -0.5, true, 1);
  live.sink().post("fader", 0.25, false, 2);
  std::vector<double> frame{5, 5};
  live.apply(0, frame);
  EXPECT_DOUBLE_EQ(frame[1], -30);
  EXPECT_DOUBLE_EQ(frame[0], 10);
  EXPECT_EQ(live.newest_taken_ns(), 2);
  frame = {5, 5};
  live.apply(0.01, frame);
  EXPECT_EQ(live.newest_taken_ns(), 0);  // nothing new
  EXPECT_DOUBLE_EQ(frame[0], 10);
}

TEST(LiveInputs, ARelativeMappingMovesFromWhereTheChannelWasAtItsRateWithinLimits) {
  ControlMapping m = live_test_mapping("x", 1, 0, 0);
  m.mode = MappingMode::relative;
  m.rate = 100;  // units/s at full deflection
  LiveInputs live(live_test_channels(), {m});
  std::vector<double> frame{0, 20};
  live.apply(0, frame);  // the show holds neck_pan at 20
  live.sink().post("x", 0.5, true, 1);
  for (int k = 1; k <= 10; ++k) {
    frame = {0, 20};
    live.apply(k * 0.01, frame);
  }
  // 10 ticks at 50 units/s from 20 (the first tick taking it over moves it by its own dt).
  EXPECT_NEAR(frame[1], 25, 1e-9);
  live.sink().post("x", 1, true, 2);
  for (int k = 11; k <= 200; ++k) {
    frame = {0, 20};
    live.apply(k * 0.01, frame);
  }
  EXPECT_DOUBLE_EQ(frame[1], 60);  // held at the channel's limit
}

TEST(LiveInputs, AHoldControlGatesItsMapping) {
  ControlMapping m = live_test_mapping("x", 1, -60, 60);
  m.hold = "button5";
  LiveInputs live(live_test_channels(), {m});
  live.sink().post("x", 1, true, 1);
  std::vector<double> frame{0, 0};
  live.apply(0, frame);
  EXPECT_DOUBLE_EQ(frame[1], 0);
  live.sink().post("button5", 1, false, 2);
  live.apply(0.01, frame);
  EXPECT_DOUBLE_EQ(frame[1], 60);
  live.sink().post("button5", 0, false, 3);
  frame = {0, 0};
  live.apply(0.02, frame);
  EXPECT_DOUBLE_EQ(frame[1], 0);
}

TEST(LiveInputs, DirectChannelControlsSetChannelUnitsAboveEveryMappingWithinLimits) {
  LiveInputs live(live_test_channels(), {live_test_mapping("fader", 0, 0, 40)});
  live.sink().post("fader", 1, false, 1);
  live.sink().post("channel/jaw", 12.5, false, 2);
  std::vector<double> frame{0, 0};
  for (int k = 0; k <= 30; ++k) {  // the direct layer's crossfade is short, not zero
    frame = {0, 0};
    live.apply(k * 0.01, frame);
    if (k % 10 == 0) live.sink().post("channel/jaw", 12.5, false, 3 + k);
  }
  EXPECT_DOUBLE_EQ(frame[0], 12.5);
  live.sink().post("channel/neck_pan", 500, false, 99);
  for (int k = 31; k <= 60; ++k) {
    frame = {0, 0};
    live.apply(k * 0.01, frame);
  }
  EXPECT_DOUBLE_EQ(frame[1], 60);
}

TEST(LiveInputs, ASilentControlHandsTheChannelBackToTheShowAfterItsTimeout) {
  ControlMapping m = live_test_mapping("fader", 0, 0, 40);
  m.timeout_s = 1.0;
  m.crossfade_s = 0.5;
  LiveInputs live(live_test_channels(), {m});
  live.sink().post("fader", 1, false, 1);
  std::vector<double> frame{0, 0};
  double peak = 0, last = 0, biggest_step = 0;
  for (int k = 0; k <= 300; ++k) {
    frame = {10, 0};
    live.apply(k * 0.01, frame);
    peak = std::max(peak, frame[0]);
    if (k > 0) biggest_step = std::max(biggest_step, std::abs(frame[0] - last));
    last = frame[0];
  }
  EXPECT_DOUBLE_EQ(peak, 40);
  EXPECT_DOUBLE_EQ(frame[0], 10);                         // back to the show
  EXPECT_LT(biggest_step, 1.5 * 0.01 / 0.5 * 30 + 1e-9);  // eased both ways
}

TEST(LiveInputs, SmoothingLagsAStepByItsTimeConstant) {
  ControlMapping m = live_test_mapping("fader", 0, 0, 40);
  m.shape.smoothing_s = 0.1;
  LiveInputs live(live_test_channels(), {m});
  live.sink().post("fader", 0, false, 1);
  std::vector<double> frame{0, 0};
  live.apply(0, frame);
  live.sink().post("fader", 1, false, 2);
  for (int k = 1; k <= 10; ++k) {
    frame = {0, 0};
    live.apply(k * 0.01, frame);
  }
  // After one time constant a first-order filter (discretised) reaches about 1 - 1/e.
  EXPECT_NEAR(frame[0] / 40, 1 - std::pow(0.1 / 0.11, 10), 1e-9);
  EXPECT_GT(frame[0], 0.6 * 40);
}

TEST(LiveInputs, RefusesAMappingOnAChannelTheRigLacks) {
  EXPECT_THROW(LiveInputs(live_test_channels(), {live_test_mapping("x", 5, 0, 1)}), std::invalid_argument);
}

}  // namespace
}  // namespace avar::control
