// The kinematics section of a rig file: a joint tree bound to channels, and its bad forms.
#include "avar/config/rig_file.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/workspace.hpp"

namespace avar::config {
namespace {

std::string kinematics_error(const std::string& text) { return avar::testing::load_error(load_rig_file, text, "rig.yaml"); }
using avar::testing::replace;


const std::string kHead = R"(name: head
links:
  head: {port: sim, maestro: {model: mini12}}
channels:
  pan:  {unit: deg, min: -60, max: 60, rest: 0}
  tilt: {unit: deg, min: -20, max: 30, rest: 0}
  jaw:  {unit: mm, min: 0, max: 20, rest: 0}
actuators:
  - {channel: pan, link: head, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}
  - {channel: tilt, link: head, device_channel: 1, calibration: {min_us: 1000, max_us: 2000}}
  - {channel: jaw, link: head, device_channel: 2, calibration: {min_us: 1000, max_us: 2000}}
kinematics:
  joints:
    neck_tilt: {parent: neck_pan, axis: [0, 1, 0], origin: {xyz: [0, 0, 0.05]}, channel: tilt, offset: 5}
    neck_pan:  {type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, 0.1]}, channel: pan}
    skull:     {type: fixed, parent: neck_tilt, origin: {xyz: [0.02, 0, 0.03], rpy: [0, 0, 0]}}
    jaw_slide: {type: prismatic, parent: skull, axis: [0, 0, -1], channel: jaw}
  effectors:
    gaze: {joint: skull, origin: {xyz: [0.08, 0, 0]}}
)";

TEST(RigKinematics, JointsInAnyOrderBindToTheirChannelsWithTheChannelsLimits) {
  const rig::Rig rig = load_rig_file(avar::testing::write_temp_file("rig.yaml", kHead));
  ASSERT_TRUE(rig.kinematics);
  const rig::RigKinematics& k = *rig.kinematics;
  ASSERT_EQ(k.model.dof(), 3u);
  ASSERT_EQ(k.bindings.size(), 3u);
  // Parents first: neck_pan, neck_tilt, then the jaw slide.
  EXPECT_EQ(k.bindings[0].channel, 0u);
  EXPECT_EQ(k.bindings[1].channel, 1u);
  EXPECT_EQ(k.bindings[2].channel, 2u);
  EXPECT_DOUBLE_EQ(k.bindings[0].scale, std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(k.bindings[2].scale, 0.001);
  EXPECT_DOUBLE_EQ(k.model.lower_limits()[0], -60 * std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(k.model.upper_limits()[1], 25 * std::numbers::pi / 180);  // (30 - offset 5) deg
  EXPECT_DOUBLE_EQ(k.model.upper_limits()[2], 0.02);
  EXPECT_DOUBLE_EQ(k.bindings[1].to_channel(k.bindings[1].to_joint(12.5)), 12.5);
  // The gaze point at q = 0: 0.1 + 0.05 + 0.03 up, 0.02 + 0.08 forward.
  kinematics::Workspace ws(k.model);
  const double q[3] = {0, 0, 0};
  ASSERT_EQ(kinematics::forward_kinematics(k.model, q, ws), Status::ok);
  const auto gaze = *k.model.find_effector("gaze");
  EXPECT_NEAR((kinematics::effector_pose(k.model, ws, gaze).translation() - Eigen::Vector3d(0.1, 0, 0.18)).norm(), 0, 1e-12);
}

TEST(RigKinematics, RejectsBadTreesWithWhereAndWhat) {
  EXPECT_EQ(kinematics_error(replace(kHead, "{type: revolute, axis: [0, 0, 1]", "{type: revolute, parent: neck_tilt, axis: [0, 0, 1]")),
            ":14:25: joint 'neck_tilt' is its own ancestor (neck_tilt -> neck_pan -> neck_tilt); expected a tree: every "
            "chain of parents ends at the base");
  EXPECT_EQ(kinematics_error(replace(kHead, "parent: neck_pan,", "parent: neck,")),
            ":14:25: unknown parent joint 'neck' of joint 'neck_tilt'; expected one of: neck_tilt, neck_pan, skull, "
            "jaw_slide (or no parent: the base)");
  EXPECT_EQ(kinematics_error(replace(kHead, "type: revolute", "type: ball")),
            ":15:23: unknown joint type 'ball' of joint 'neck_pan'; expected one of: revolute, prismatic, fixed");
  EXPECT_NE(kinematics_error(replace(kHead, "axis: [0, 0, 1]", "axis: [0, 0, 0]")).find("axis"), std::string::npos);
  EXPECT_EQ(kinematics_error(replace(kHead, ", channel: pan}", "}")),
            ":15:16: missing field 'channel' in joint 'neck_pan' (the channel that drives it)");
  EXPECT_EQ(kinematics_error(replace(kHead, "jaw:  {unit: mm", "jaw:  {unit: notches")),
            ":17:76: channel 'jaw' is in 'notches', which joint 'jaw_slide' cannot convert; expected the channel's unit "
            "to be m, cm or mm, or a scale (joint metres per channel unit)");
  EXPECT_EQ(kinematics_error(replace(kHead, "{type: fixed, parent: neck_tilt,", "{type: fixed, axis: [1, 0, 0], parent: neck_tilt,")),
            ":16:36: axis does not apply to the fixed joint 'skull'");
  EXPECT_EQ(kinematics_error(replace(kHead, "{joint: skull,", "{joint: nose,")),
            ":19:19: unknown joint 'nose' for effector 'gaze'; expected one of: neck_tilt, neck_pan, skull, jaw_slide");
  EXPECT_EQ(kinematics_error(replace(kHead, "axis: [0, 1, 0]", "axis: [0, 1]")),
            ":14:41: expected the axis of joint 'neck_tilt' to have 3 numbers [x, y, z], found 2");
}

const std::string kImported = R"(name: imported
links:
  head: {port: sim, maestro: {model: mini12}}
channels:
  pan:  {unit: deg, min: -60, max: 60, rest: 0}
  tilt: {unit: deg, min: -20, max: 60, rest: 0}
actuators:
  - {channel: pan, link: head, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}
  - {channel: tilt, link: head, device_channel: 1, calibration: {min_us: 1000, max_us: 2000}}
kinematics:
  urdf: )" AVAR_SOURCE_DIR R"(/tests/kinematics/fixtures/pan_tilt_head.urdf
  joints:
    pan: {channel: pan}
    tilt: {channel: tilt}
)";

TEST(RigKinematics, AUrdfBindsItsJointsToChannelsWithTheNarrowerLimits) {
  const rig::Rig rig = load_rig_file(avar::testing::write_temp_file("rig.yaml", kImported));
  ASSERT_TRUE(rig.kinematics);
  const kinematics::Model& m = rig.kinematics->model;
  ASSERT_EQ(m.dof(), 2u);
  EXPECT_TRUE(m.find_effector("eye"));
  // pan: URDF ±1.5 rad, channel ±60° = ±1.047 rad; tilt: URDF [-0.6, 0.8], channel [-20°, 60°].
  EXPECT_NEAR(m.lower_limits()[0], -60 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(m.upper_limits()[1], 0.8, 1e-12);
  EXPECT_NEAR(m.lower_limits()[1], -20 * std::numbers::pi / 180, 1e-12);
  EXPECT_EQ(kinematics_error(replace(kImported, "    tilt: {channel: tilt}\n", "")),
            ":13:5: joint 'tilt' has no channel; expected tilt: {channel: ...} among the joints");
  EXPECT_EQ(kinematics_error(replace(kImported, "    tilt: {channel: tilt}", "    tilt: {channel: tilt}\n    roll: {channel: pan}")),
            ":15:5: unknown movable joint 'roll'; expected one of: pan, tilt");
}

TEST(RigKinematics, ADenavitHartenbergChainBindsJoint1ToN) {
  const std::string dh = replace(replace(kImported, "  urdf: " AVAR_SOURCE_DIR "/tests/kinematics/fixtures/pan_tilt_head.urdf",
                                         "  dh:\n    convention: standard\n    rows: [{d: 0.1, alpha: -1.5707963267948966}, {a: 0.2}]"),
                                 "    pan: {channel: pan}\n    tilt: {channel: tilt}", "    joint1: {channel: pan}\n    joint2: {channel: tilt}");
  const rig::Rig rig = load_rig_file(avar::testing::write_temp_file("rig.yaml", dh));
  ASSERT_TRUE(rig.kinematics);
  EXPECT_EQ(rig.kinematics->model.dof(), 2u);
  EXPECT_TRUE(rig.kinematics->model.find_effector("tip"));
  EXPECT_NE(kinematics_error(replace(dh, "convention: standard", "convention: craig")).find("unknown DH convention 'craig'; expected one of: standard, modified"),
            std::string::npos);
}

}  // namespace
}  // namespace avar::config
