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

ControlMapping live_target_mapping(std::string control, std::size_t effector, std::size_t axis, double low, double high) {
  ControlMapping m = live_test_mapping(std::move(control), 0, low, high);
  m.output = MappingOutput::target;
  m.effector = effector;
  m.axis = axis;
  return m;
}

TEST(LiveInputs, ATargetMappingMovesOneAxisOfItsEffectorsGoalAndLeavesTheRest) {
  // Two effectors, eyes and hand; the stick drives the eyes' y from -0.5 m to 0.5 m.
  LiveInputs live(live_test_channels(), {live_target_mapping("x", 0, 1, -0.5, 0.5)}, {"eyes", "hand"});
  const double nan = std::nan("");
  std::vector<double> points{1, -0.8, 0.3, nan, nan, nan};  // the show moves the eyes only
  live.apply_targets(0, points);
  EXPECT_EQ(points[1], -0.8);  // nothing posted: the show's goal
  live.sink().post("x", 0.6, true, 7);
  points = {1, -0.8, 0.3, nan, nan, nan};
  live.apply_targets(0.02, points);
  EXPECT_DOUBLE_EQ(points[0], 1);
  EXPECT_DOUBLE_EQ(points[1], 0.3);
  EXPECT_DOUBLE_EQ(points[2], 0.3);
  for (std::size_t k = 3; k < 6; ++k) EXPECT_TRUE(std::isnan(points[k])) << k;
  // The channels are not touched by it; the arrival is reported once the tick's mix is done.
  std::vector<double> frame{12, 34};
  live.apply(0.02, frame);
  EXPECT_DOUBLE_EQ(frame[0], 12);
  EXPECT_DOUBLE_EQ(frame[1], 34);
  EXPECT_EQ(live.newest_taken_ns(), 7);
  EXPECT_TRUE(live.target_mixer().active(0));
}

TEST(LiveInputs, ARelativeTargetMappingMovesFromTheShowsGoalWithinItsBounds) {
  ControlMapping m = live_target_mapping("x", 0, 2, 0.1, 0.5);
  m.mode = MappingMode::relative;
  m.rate = 0.2;  // m/s at full deflection
  LiveInputs live(live_test_channels(), {m}, {"eyes"});
  std::vector<double> points{1, 0, 0.3};
  live.apply_targets(0, points);
  live.sink().post("x", 1.0, true, 1);
  for (int k = 1; k <= 150; ++k) {
    points = {1, 0, 0.3};
    live.apply_targets(k * 0.01, points);
    if (k == 10) {
      EXPECT_NEAR(points[2], 0.32, 1e-12);  // from the show's 0.3 at 0.2 m/s
    }
  }
  EXPECT_DOUBLE_EQ(points[2], 0.5);  // held at the bound
}

TEST(LiveInputs, RefusesATargetMappingOnAnEffectorTheRigLacks) {
  EXPECT_THROW(LiveInputs(live_test_channels(), {live_target_mapping("x", 1, 0, 0, 1)}, {"eyes"}), std::invalid_argument);
  EXPECT_THROW(LiveInputs(live_test_channels(), {live_target_mapping("x", 0, 3, 0, 1)}, {"eyes"}), std::invalid_argument);
}

}  // namespace
}  // namespace avar::control
