#include "avar/config/input_map.hpp"

#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

const char* kInputMapRig = R"(name: puppet
links:
  head: {port: sim, maestro: {model: mini12}}
channels:
  jaw: {unit: deg, min: 0, max: 30, rest: 0}
  pan: {unit: deg, min: -60, max: 60, rest: 0, soft_margin: 2}
actuators:
  - {channel: jaw, link: head, device_channel: 0, calibration: {min_us: 1200, max_us: 1650}}
  - {channel: pan, link: head, device_channel: 1, calibration: {min_us: 1000, max_us: 2000}}
)";

const char* kInputs = R"(inputs:
  devices: [osc://127.0.0.1:9000, "midi:nano"]
  mappings:
    - {control: ch1.cc0, channel: jaw, range: [0, 25], input: [0, 127], dead_zone: 0.05, expo: 0.3,
       smoothing: 0.05, invert: true, priority: 20, blend: additive, crossfade: 0.5, timeout: 2}
    - {control: x, channel: pan, mode: relative, rate: 90, hold: button5}
)";

rig::Rig input_map_rig() { return load_rig_file(testing::write_temp_file("input_map_rig.yaml", kInputMapRig)); }

std::string input_map_error(const std::string& text) {
  const rig::Rig rig = input_map_rig();
  return testing::load_error([&](const std::string& path) { (void)load_input_map(rig, path, true); }, text,
                             "inputs_under_test.yaml");
}

TEST(InputMap, ReadsDevicesAndEveryMappingField) {
  const rig::Rig rig = input_map_rig();
  const InputMap map = load_input_map(rig, testing::write_temp_file("inputs.yaml", kInputs), true);
  ASSERT_EQ(map.devices.size(), 2u);
  EXPECT_EQ(map.devices[1], "midi:nano");
  ASSERT_EQ(map.mappings.size(), 2u);
  const control::ControlMapping& jaw = map.mappings[0];
  EXPECT_EQ(jaw.control, "ch1.cc0");
  EXPECT_EQ(jaw.channel, 0u);
  EXPECT_DOUBLE_EQ(jaw.low, 0);
  EXPECT_DOUBLE_EQ(jaw.high, 25);
  ASSERT_TRUE(jaw.shape.input);
  EXPECT_DOUBLE_EQ(jaw.shape.input->second, 127);
  EXPECT_DOUBLE_EQ(jaw.shape.dead_zone, 0.05);
  EXPECT_DOUBLE_EQ(jaw.shape.expo, 0.3);
  EXPECT_DOUBLE_EQ(jaw.shape.smoothing_s, 0.05);
  EXPECT_TRUE(jaw.shape.invert);
  EXPECT_EQ(jaw.priority, 20);
  EXPECT_EQ(jaw.blend, control::Blend::additive);
  EXPECT_DOUBLE_EQ(jaw.crossfade_s, 0.5);
  EXPECT_DOUBLE_EQ(jaw.timeout_s, 2);
  const control::ControlMapping& pan = map.mappings[1];
  EXPECT_EQ(pan.mode, control::MappingMode::relative);
  EXPECT_DOUBLE_EQ(pan.rate, 90);
  EXPECT_EQ(pan.hold, "button5");
  EXPECT_DOUBLE_EQ(pan.low, -60);  // an absolute default would be the limits
}

TEST(InputMap, AnAdditiveRangeIsAnOffsetWithinTheChannelsSpan) {
  const rig::Rig rig = input_map_rig();
  const InputMap map = load_input_map(
      rig,
      testing::write_temp_file("additive.yaml",
                               "inputs:\n  mappings:\n    - {control: b, channel: jaw, blend: additive, range: [0, -20]}\n"),
      true);
  EXPECT_DOUBLE_EQ(map.mappings[0].high, -20);
  EXPECT_NE(input_map_error("inputs:\n  mappings:\n    - {control: b, channel: jaw, blend: additive, range: [0, -31]}\n")
                .find("within the span of channel 'jaw' (±30)"),
            std::string::npos);
}

TEST(InputMap, AMappingMayDriveOneAxisOfAnInverseKinematicsTarget) {
  const rig::Rig rig = load_rig_file(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-head.yaml");
  const InputMap map = load_input_map(
      rig,
      testing::write_temp_file("targets.yaml",
                               "inputs:\n  mappings:\n"
                               "    - {control: x, target: eyes, axis: y, range: [-1, 1]}\n"
                               "    - {control: y, target: eyes, axis: z, range: [0, 1], mode: relative, rate: 0.5}\n"),
      true);
  ASSERT_EQ(map.mappings.size(), 2u);
  EXPECT_EQ(map.mappings[0].output, control::MappingOutput::target);
  EXPECT_EQ(map.mappings[0].effector, 0u);
  EXPECT_EQ(map.mappings[0].axis, 1u);
  EXPECT_DOUBLE_EQ(map.mappings[0].low, -1);
  EXPECT_EQ(map.mappings[1].axis, 2u);
  EXPECT_EQ(map.mappings[1].mode, control::MappingMode::relative);
  EXPECT_DOUBLE_EQ(map.mappings[1].rate, 0.5);
  EXPECT_EQ(live_effectors(rig), std::vector<std::string>{"eyes"});
  const InputMap example = load_input_map(rig, std::string(AVAR_SOURCE_DIR) + "/examples/inputs/gaze-head-stick.yaml", true);
  EXPECT_EQ(example.mappings.size(), 2u);
}

TEST(InputMap, ATargetMappingNamesAnEffectorAnAxisAndARangeInMetres) {
  const std::string rig_path = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-head.yaml";
  const rig::Rig rig = load_rig_file(rig_path);
  const auto error = [&](const std::string& mapping) {
    return testing::load_error([&](const std::string& path) { (void)load_input_map(rig, path, true); },
                               "inputs:\n  mappings:\n    - " + mapping + "\n", "target_inputs.yaml");
  };
  EXPECT_NE(error("{control: x, target: hand, axis: y, range: [-1, 1]}")
                .find("unknown target 'hand'; expected one of the kinematics' effectors: eyes"),
            std::string::npos);
  EXPECT_NE(error("{control: x, target: eyes, axis: w, range: [-1, 1]}").find("to be x, y or z"), std::string::npos);
  EXPECT_NE(error("{control: x, target: eyes, axis: y}").find("range"), std::string::npos);
  EXPECT_NE(error("{control: x, target: eyes, axis: y, range: [-1, 1000]}").find("within ±100"), std::string::npos);
  EXPECT_NE(error("{control: x, target: eyes, channel: jaw, axis: y, range: [-1, 1]}").find("not both"), std::string::npos);
  EXPECT_NE(error("{control: x, channel: jaw, axis: y}").find("an axis applies to a target mapping only"), std::string::npos);
  // A rig without kinematics has no targets to steer.
  EXPECT_NE(input_map_error("inputs:\n  mappings:\n    - {control: x, target: eyes, axis: y, range: [-1, 1]}\n")
                .find("needs the rig's kinematics: section"),
            std::string::npos);
}

TEST(InputMap, ARigFileMayCarryItsOwnInputsSection) {
  const std::string path = testing::write_temp_file("rig_with_inputs.yaml", std::string(kInputMapRig) + kInputs);
  const rig::Rig rig = load_rig_file(path);
  EXPECT_EQ(load_input_map(rig, path, false).mappings.size(), 2u);
  EXPECT_TRUE(load_input_map(rig, testing::write_temp_file("no_inputs.yaml", kInputMapRig), false).mappings.empty());
}

TEST(InputMap, LiveChannelsKeepInsideTheSoftMargins) {
  const std::vector<control::LiveChannel> channels = live_channels(input_map_rig());
  EXPECT_DOUBLE_EQ(channels[1].min, -58);
  EXPECT_DOUBLE_EQ(channels[1].max, 58);
}

TEST(InputMap, RefusesEveryBadFieldWithItsLocation) {
  using testing::replace;
  EXPECT_NE(input_map_error("devices: []\n").find(":1:1: expected an inputs: section"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "channel: jaw", "channel: nose")).find(":4:35: unknown channel 'nose'"),
            std::string::npos)
      << input_map_error(replace(kInputs, "channel: jaw", "channel: nose"));
  EXPECT_NE(input_map_error(replace(replace(kInputs, "range: [0, 25]", "range: [0, 45]"), "blend: additive", "blend: override"))
                .find("inside the limits of channel 'jaw' [0, 30]"),
            std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "rate: 90, ", "")).find("expected a rate"), std::string::npos);
  EXPECT_NE(
      input_map_error(replace(kInputs, "mode: relative, rate: 90", "rate: 90")).find("a rate applies to mode: relative only"),
      std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "dead_zone: 0.05", "dead_zone: 1")).find("dead_zone"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "expo: 0.3", "expo: 2")).find("expo"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "blend: additive", "blend: mix")).find("override or additive"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "input: [0, 127]", "input: [5, 5]")).find("two different values"),
            std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "control: x,", "control: 'a b',")).find("a control name"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "timeout: 2", "timout: 2")).find("timout"), std::string::npos);
  EXPECT_NE(input_map_error(replace(kInputs, "priority: 20", "priority: 1000")).find("-999 to 999"), std::string::npos);
}

TEST(InputMap, EveryBundledInputsFileFitsTheRigItIsFor) {
  const rig::Rig rig = load_rig_file(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml");
  for (const char* name : {"hello-head-osc.yaml", "hello-head-gamepad.yaml", "hello-head-midi.yaml"}) {
    const InputMap map = load_input_map(rig, std::string(AVAR_SOURCE_DIR) + "/examples/inputs/" + name, true);
    EXPECT_FALSE(map.devices.empty()) << name;
    EXPECT_GE(map.mappings.size(), 4u) << name;
  }
}

}  // namespace
}  // namespace avar::config
