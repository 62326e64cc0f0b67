// The retarget map: a good map binds rotations to channels and positions to IK targets; every
// malformed form is refused with file:line:col and what was expected.
#include "avar/config/retarget_map.hpp"

#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

const std::string kRetargetGazeRig = AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml";

const std::string kRetargetMap = R"(retarget:
  source_units: 0.01
  rotations:
    - {joint: Jaw, channel: jaw, axis: x, order: zxy, scale: 0.5, offset: 2, reverse: true}
  positions:
    - joint: RightHand
      target: eyes
      origin: Hips
      axes: [x, -z, y]
      offset: [0.5, 0, 0.3]
      scale: 2
)";

std::string retarget_map_error(const std::string& text) {
  const rig::Rig rig = load_rig_file(kRetargetGazeRig);
  return avar::testing::load_error([&rig](const std::string& path) { (void)load_retarget_map(path, rig); }, text, "map.yaml");
}
using avar::testing::replace;

TEST(RetargetMapFile, ReadsRotationsAndPositions) {
  const rig::Rig rig = load_rig_file(kRetargetGazeRig);
  const std::string path = avar::testing::write_temp_file("map.yaml", kRetargetMap);
  const mocap::RetargetMap map = load_retarget_map(path, rig);
  EXPECT_DOUBLE_EQ(map.source_units, 0.01);
  ASSERT_EQ(map.rotations.size(), 1u);
  const mocap::RotationBinding& r = map.rotations[0];
  EXPECT_EQ(r.joint, "Jaw");
  EXPECT_EQ(r.joint_where.line, 4);
  EXPECT_EQ(r.channel, "jaw");
  EXPECT_EQ(r.axis, 0);
  EXPECT_EQ(r.order, playback::EulerOrder::zxy);
  EXPECT_EQ(r.relative_to, mocap::RelativeTo::rest);
  EXPECT_DOUBLE_EQ(r.scale, 0.5);
  EXPECT_DOUBLE_EQ(r.offset, 2);
  EXPECT_TRUE(r.reverse);
  EXPECT_EQ(r.units, mocap::AngleUnit::deg);
  ASSERT_EQ(map.positions.size(), 1u);
  const mocap::PositionBinding& p = map.positions[0];
  EXPECT_EQ(p.target, "eyes");
  EXPECT_EQ(p.origin, "Hips");
  EXPECT_EQ(p.origin_where.line, 8);
  EXPECT_EQ(p.from, (std::array<int, 3>{0, 2, 1}));
  EXPECT_EQ(p.sign, (std::array<double, 3>{1, -1, 1}));
  EXPECT_DOUBLE_EQ(p.offset.x(), 0.5);
  EXPECT_DOUBLE_EQ(p.scale, 2);
}

TEST(RetargetMapFile, RefusesMalformedMapsWithWhereAndWhat) {
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "channel: jaw", "channel: chin")),
            ":4:29: unknown channel 'chin'; expected one of the rig's channels: neck_pan, neck_tilt, jaw");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "axis: x", "axis: w")),
            ":4:40: expected the axis of rotation 1 to be x, y or z, found 'w'");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "order: zxy", "order: zxz")),
            ":4:50: expected the order of rotation 1 to be one of xyz, xzy, yxz, yzx, zxy, zyx, found 'zxz'");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "order: zxy, ", "")),
            ":4:7: missing field 'order' in rotation 1 (the Euler decomposition order, e.g. zxy)");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "reverse: true}", "reverse: true, units: rad}")),
            ":4:100: found units rad for channel 'jaw', which is in deg; expected deg (or leave units out)");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "scale: 0.5", "scael: 0.5")),
            ":4:55: unknown field 'scael' in rotation 1; expected one of: joint, channel, axis, order, relative_to, scale, "
            "offset, reverse, units");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "target: eyes", "target: hand")),
            ":7:15: unknown effector 'hand'; expected one of the rig's effectors: eyes");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "[x, -z, y]", "[x, -z, x]")),
            ":9:21: file axis x appears twice in the axes of position 1; expected each of x, y, z once");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "[x, -z, y]", "[x, -z]")),
            ":9:13: expected the axes of position 1 as [a, b, c], the file axis (x, y, z, -x, -y or -z) for each rig axis, "
            "found a list");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "source_units: 0.01", "source_units: -1")),
            ":2:17: expected source_units (metres per file unit) above 0, found '-1'");
  EXPECT_EQ(retarget_map_error(replace(kRetargetMap, "channel: jaw", "channel: neck_pan")),
            ":4:29: channel 'neck_pan' is moved by target 'eyes' (inverse kinematics, line 6) and also by this rotation; "
            "expected one or the other");
  EXPECT_EQ(retarget_map_error(
                replace(kRetargetMap, "  positions:", "    - {joint: Head, channel: jaw, axis: y, order: xyz}\n  positions:")),
            ":5:30: channel 'jaw' is already driven by the binding at line 4; expected each channel and target driven once");
  EXPECT_EQ(retarget_map_error("retarget: {source_units: 1}\n"),
            ":1:11: found no bindings; expected rotations: or positions: with at least one entry");
  EXPECT_EQ(retarget_map_error("retarget:\n  rotations:\n    - {joint: Jaw, channel: jaw, axis: x, order: zxy\n"),
            ":4:1: malformed YAML: end of map flow not found");
}

TEST(RetargetMapFile, PositionsNeedARigWithKinematics) {
  const rig::Rig rig = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  const std::string error = avar::testing::load_error([&rig](const std::string& path) { (void)load_retarget_map(path, rig); },
                                                      "retarget:\n  positions:\n    - {joint: Hand, target: hand}\n", "map.yaml");
  EXPECT_EQ(error,
            ":3:29: target 'hand' needs inverse kinematics, but rig 'hello-head' has no kinematics section; expected a "
            "rig with joints and effectors");
}

}  // namespace
}  // namespace avar::config
