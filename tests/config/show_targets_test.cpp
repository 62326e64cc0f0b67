// Targets in show files: points for the rig's effectors, solved by inverse kinematics, and the
// checks that tie them to a rig.
#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"

namespace avar::config {
namespace {

std::string targets_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }
using avar::testing::replace;


const std::string kTargetsRig = AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml";

const std::string kTargetsShow = R"(name: look
duration: 4
targets:
  eyes:
    aim: [1, 0, 0]
    x: [{time: 0, value: 1}]
    y: [{time: 0, value: -0.5}, {time: 4, value: 0.5}]
    z: {extrapolation: linear, keys: [{time: 0, value: 0.3}, {time: 2, value: 0.5}]}
tracks:
  jaw: [{time: 0, value: 0}, {time: 1, value: 10}]
)";

TEST(ShowTargets, CurvesAndStaticPointsLoad) {
  const playback::Show show = load_show_file(avar::testing::write_temp_file("show.yaml", kTargetsShow));
  ASSERT_EQ(show.targets.size(), 1u);
  const playback::TargetTrack& t = show.targets[0];
  EXPECT_EQ(t.effector, "eyes");
  EXPECT_EQ(t.kind, playback::TargetKind::aim);
  EXPECT_DOUBLE_EQ(t.xyz[0].evaluate(3), 1);
  EXPECT_DOUBLE_EQ(t.xyz[1].evaluate(2), 0);
  EXPECT_DOUBLE_EQ(t.xyz[2].evaluate(3), 0.6);  // linear extrapolation
  const playback::Show still = load_show_file(avar::testing::write_temp_file(
      "still.yaml", "duration: 1\ntargets:\n  eyes: {point: [1, 0.2, 0.4]}\n"));
  ASSERT_EQ(still.targets.size(), 1u);
  EXPECT_EQ(still.targets[0].kind, playback::TargetKind::position);
  EXPECT_DOUBLE_EQ(still.targets[0].xyz[2].evaluate(0.5), 0.4);
  EXPECT_TRUE(still.tracks.empty());
}

TEST(ShowTargets, OrientationsAndPosesLoad) {
  const playback::Show show = load_show_file(avar::testing::write_temp_file(
      "pose.yaml", R"(duration: 2
targets:
  hand:
    point: [0.3, 0.1, 0.2]
    roll: [{time: 0, value: 0}, {time: 2, value: 1}]
    pitch: [{time: 0, value: 0.5}]
    yaw: [{time: 0, value: -0.5}]
  wrist: {orientation: [0, 1.5707963267948966, 0]}
)"));
  ASSERT_EQ(show.targets.size(), 2u);
  EXPECT_EQ(show.targets[0].kind, playback::TargetKind::pose);
  EXPECT_DOUBLE_EQ(show.targets[0].rpy[0].evaluate(1), 0.5);
  EXPECT_DOUBLE_EQ(show.targets[0].xyz[1].evaluate(1), 0.1);
  EXPECT_EQ(show.targets[1].kind, playback::TargetKind::orientation);
  EXPECT_DOUBLE_EQ(show.targets[1].rpy[1].evaluate(0), 1.5707963267948966);
}

TEST(ShowTargets, BadTargetsAreRejectedWithWhereAndWhat) {
  EXPECT_EQ(targets_error(replace(kTargetsShow, "aim: [1, 0, 0]", "aim: [0, 0, 0]")),
            ":5:10: expected the aim axis of target 'eyes' to be a non-zero direction, found [0, 0, 0]");
  EXPECT_EQ(targets_error(replace(kTargetsShow, "    x: [{time: 0, value: 1}]\n", "")),
            ":5:5: missing field 'x' in target 'eyes' (a static point, or x, y and z curves in m)");
  EXPECT_EQ(targets_error(replace(kTargetsShow, "aim: [1, 0, 0]", "aim: [1, 0, 0]\n    point: [1, 2, 3]")),
            ":7:8: target 'eyes' has both point and x; expected a static point or three curves");
  EXPECT_EQ(targets_error(replace(kTargetsShow, "aim: [1, 0, 0]", "look: [1, 0, 0]")),
            ":5:5: unknown field 'look' in target 'eyes'; expected one of: aim, point, x, y, z, path, orientation, roll, pitch, yaw, orientation_keys");
  EXPECT_EQ(targets_error(replace(kTargetsShow, "aim: [1, 0, 0]", "aim: [1, 0, 0]\n    orientation: [0, 0, 1]")),
            ":5:10: target 'eyes' both aims and sets an orientation; expected one or the other");
}

TEST(ShowTargets, TheRigMustHaveTheEffectorAndTracksMustNotFightTheSolver) {
  const rig::Rig rig = load_rig_file(kTargetsRig);
  const auto check = [&](const std::string& text) {
    return check_show_against_rig(load_show_file(avar::testing::write_temp_file("show.yaml", text)), rig);
  };
  EXPECT_TRUE(check(kTargetsShow).ok());
  const ShowCheck unknown = check(replace(kTargetsShow, "  eyes:", "  nose:"));
  ASSERT_EQ(unknown.errors.size(), 1u);
  EXPECT_NE(unknown.errors[0].message.find("unknown effector 'nose'; expected one of the rig's effectors: eyes"), std::string::npos);
  const ShowCheck both = check(replace(kTargetsShow, "  jaw:", "  neck_pan: [{time: 0, value: 0}]\n  jaw:"));
  ASSERT_EQ(both.errors.size(), 1u);
  EXPECT_EQ(both.errors[0].message,
            "channel 'neck_pan' is moved by target 'eyes' (inverse kinematics) and also has a track; expected one or the other");
  const rig::Rig plain = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  const ShowCheck no_kinematics = check_show_against_rig(load_show_file(avar::testing::write_temp_file("show.yaml", kTargetsShow)), plain);
  ASSERT_FALSE(no_kinematics.ok());
  EXPECT_NE(no_kinematics.errors.back().message.find("has no kinematics section"), std::string::npos);
}

}  // namespace
}  // namespace avar::config
