// `avar mocap bake` and `avar play FILE.bvh --map MAP` end to end: the example head BVH baked onto
// hello-head (hand-computed channel values, fitted within the tolerance, accepted by `avar
// check`), played directly; a hand position retargeted onto an IK target that the played arm
// reaches; malformed maps and mocap files refused with their location, nothing written or played.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"
#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kBakeHeadRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";
const std::string kBakeNodBvh = AVAR_SOURCE_DIR "/examples/mocap/nod.bvh";
const std::string kBakeHeadMap = AVAR_SOURCE_DIR "/examples/mocap/hello-head-map.yaml";

double bake_value(const playback::Show& show, const std::string& channel, double t) {
  for (const playback::Track& track : show.tracks)
    if (track.channel == channel) return track.curve.evaluate(t);
  ADD_FAILURE() << "no track for " << channel;
  return NAN;
}

TEST(MocapBake, BakesTheExampleHeadWithinTheToleranceAndTheShowChecks) {
  const std::string out = avar::testing::temp_path("nod.yaml");
  const testing::CliResult bake = testing::run_avar(
      {"mocap", "bake", kBakeNodBvh, "--map", kBakeHeadMap, "--rig", kBakeHeadRig, "--out", out, "--tolerance", "0.2"});
  ASSERT_EQ(bake.code, kExitOk) << bake.err << bake.out;
  EXPECT_NE(bake.out.find("neck_pan: 121 samples in"), std::string::npos) << bake.out;
  EXPECT_NE(bake.out.find("ok: show 'nod'"), std::string::npos) << bake.out;
  EXPECT_NE(bake.err.find("fitting 4/4: jaw"), std::string::npos) << bake.err;  // progress
  const playback::Show show = config::load_show_file(out);
  EXPECT_NEAR(show.duration, 4, 1e-3);
  // The generator's motion (make_nod_bvh.py) through the map, at every frame time.
  for (int frame = 0; frame <= 120; ++frame) {
    const double t = frame / 30.0;
    const double jaw = (t >= 1.0 && t <= 3.4) ? 9 - 9 * std::cos(2 * std::numbers::pi * (t - 1.0) / 0.8) : 0.0;
    // 2e-3: the file's frame time (0.0333333) and its 4 decimals of angle.
    EXPECT_NEAR(bake_value(show, "neck_pan", t), 35 * std::sin(2 * std::numbers::pi * t / 4), 0.2 + 2e-3) << t;
    EXPECT_NEAR(bake_value(show, "neck_tilt", t), -10 * std::sin(2 * std::numbers::pi * t / 1.6), 0.2 + 2e-3) << t;
    EXPECT_NEAR(bake_value(show, "neck_roll", t), 6 * std::sin(2 * std::numbers::pi * t / 2.0), 0.2 + 2e-3) << t;
    EXPECT_NEAR(bake_value(show, "jaw", t), 1.5 * jaw + 0.1, 0.2 + 2e-3) << t;
  }
  const testing::CliResult check = testing::run_avar({"check", out, "--rig", kBakeHeadRig});
  ASSERT_EQ(check.code, kExitOk) << check.err << check.out;
  EXPECT_NE(check.out.find("0 segment(s) ask more"), std::string::npos) << check.out;
}

TEST(MocapBake, BakesAGltfFileSampledAtTheAskedRate) {
  // The fixture's joint 'spin' turns from rest to 90 deg about y over 1 s (slerp: 90 t deg).
  const std::string glb = AVAR_SOURCE_DIR "/tests/data/mocap/gltf_short_rotation.glb";
  const std::string map = avar::testing::write_temp_file(
      "map.yaml", "retarget:\n  rotations:\n    - {joint: spin, channel: neck_pan, axis: y, order: xyz, scale: 0.5}\n");
  const std::string out = avar::testing::temp_path("spin.yaml");
  const testing::CliResult bake = testing::run_avar({"mocap", "bake", glb, "--map", map, "--rig", kBakeHeadRig, "--out", out,
                                                     "--fps", "10", "--tolerance", "0.1", "--no-progress"});
  ASSERT_EQ(bake.code, kExitOk) << bake.err << bake.out;
  EXPECT_NE(bake.out.find("neck_pan: 11 samples in"), std::string::npos) << bake.out;
  const playback::Show show = config::load_show_file(out);
  for (int i = 0; i <= 10; ++i) EXPECT_NEAR(bake_value(show, "neck_pan", i / 10.0), 4.5 * i, 0.1 + 1e-9) << i;
}

TEST(MocapBake, PlaysAMocapFileDirectlyThroughAMap) {
  const testing::CliResult play =
      testing::run_avar({"play", kBakeNodBvh, "--map", kBakeHeadMap, "--rig", kBakeHeadRig, "--sim", "--fast", "--no-progress"});
  ASSERT_EQ(play.code, kExitOk) << play.err << play.out;
  EXPECT_NE(play.out.find("played 'nod' on rig 'hello-head'"), std::string::npos) << play.out;
}

TEST(MocapBake, MalformedMapsAndFilesAreRefusedWithTheirPlaceAndNothingPlays) {
  std::ifstream in(kBakeHeadMap);
  std::stringstream text;
  text << in.rdbuf();
  const std::string good = text.str();
  struct Case {
    std::string from, to, expected;
  };
  const Case cases[] = {
      {"channel: neck_roll", "channel: neck_rol", "unknown channel 'neck_rol'"},
      {"joint: Jaw", "joint: Chin",
       "unknown joint 'Chin' in " + kBakeNodBvh + "; expected one of its joints: Hips, Neck, Head, Jaw"},
      {"axis: z", "axis: q", "expected the axis of rotation 3 to be x, y or z"},
      {"scale: 1.5", "scale: 5", "channel 'jaw' reaches 33.453 deg at 1.16667 s, outside its limits [0, 30]"},
  };
  for (const Case& c : cases) {
    const std::string map = avar::testing::write_temp_file("map.yaml", avar::testing::replace(good, c.from, c.to));
    const std::size_t line = [&] {
      const std::string edited = avar::testing::replace(good, c.from, c.to);
      return static_cast<std::size_t>(std::count(edited.begin(), edited.begin() + static_cast<long>(edited.find(c.to)), '\n') +
                                      1);
    }();
    const testing::CliResult play =
        testing::run_avar({"play", kBakeNodBvh, "--map", map, "--rig", kBakeHeadRig, "--sim", "--fast", "--no-progress"});
    EXPECT_EQ(play.code, kExitBadInput) << c.to;
    EXPECT_NE(play.err.find("error: " + map + ":" + std::to_string(line) + ":"), std::string::npos) << play.err;
    EXPECT_NE(play.err.find(c.expected), std::string::npos) << play.err;
    EXPECT_EQ(play.out.find("played"), std::string::npos) << play.out;
    const std::string out = avar::testing::temp_path("never.yaml");
    const testing::CliResult bake =
        testing::run_avar({"mocap", "bake", kBakeNodBvh, "--map", map, "--rig", kBakeHeadRig, "--out", out, "--no-progress"});
    EXPECT_EQ(bake.code, kExitBadInput) << c.to;
    EXPECT_NE(bake.err.find(c.expected), std::string::npos) << bake.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.to;
  }
  // A broken BVH: the reader's place in the file.
  const std::string bvh = avar::testing::write_temp_file("broken.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
  const testing::CliResult broken =
      testing::run_avar({"play", bvh, "--map", kBakeHeadMap, "--rig", kBakeHeadRig, "--sim", "--fast", "--no-progress"});
  EXPECT_EQ(broken.code, kExitBadInput);
  EXPECT_NE(broken.err.find("error: " + bvh + ":4:"), std::string::npos) << broken.err;
  // A mocap file needs a map, and a map needs a mocap file.
  const testing::CliResult no_map = testing::run_avar({"play", kBakeNodBvh, "--rig", kBakeHeadRig, "--sim", "--fast"});
  EXPECT_EQ(no_map.code, kExitBadInput);
  EXPECT_NE(no_map.err.find("expected --map MAP.yaml"), std::string::npos) << no_map.err;
  const testing::CliResult map_on_show = testing::run_avar({"play", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--map",
                                                            kBakeHeadMap, "--rig", kBakeHeadRig, "--sim", "--fast"});
  EXPECT_EQ(map_on_show.code, kExitBadInput);
}

TEST(MocapBake, ClampRetargetsWhatTheLimitsRefuse) {
  const std::string map = avar::testing::write_temp_file(
      "map.yaml", "retarget:\n  rotations:\n    - {joint: Jaw, channel: jaw, axis: x, order: yxz, scale: 5}\n");
  const std::string out = avar::testing::temp_path("clamped.yaml");
  const testing::CliResult bake = testing::run_avar(
      {"mocap", "bake", kBakeNodBvh, "--map", map, "--rig", kBakeHeadRig, "--out", out, "--clamp", "--no-progress"});
  ASSERT_EQ(bake.code, kExitOk) << bake.err << bake.out;
  EXPECT_NE(bake.out.find("samples clamped into the limits"), std::string::npos) << bake.out;
  const playback::Show show = config::load_show_file(out);
  for (const auto& key : show.tracks.at(0).raw.keys) EXPECT_LE(key.value, 30);
}

// A three-joint arm (base yaw, shoulder and elbow pitch) whose hand is an IK effector.
const std::string kBakeArmRig = R"(name: bake-arm
rate_hz: 100
links:
  arm: {port: sim, maestro: {model: mini12}}
channels:
  base:     {unit: deg, min: -90, max: 90,  rest: 0,  max_velocity: 180}
  shoulder: {unit: deg, min: -90, max: 100, rest: 0, max_velocity: 180}
  elbow:    {unit: deg, min: 0,   max: 150, rest: 90, max_velocity: 180}
actuators:
  - {channel: base,     link: arm, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}
  - {channel: shoulder, link: arm, device_channel: 1, calibration: {min_us: 1000, max_us: 2000}}
  - {channel: elbow,    link: arm, device_channel: 2, calibration: {min_us: 1000, max_us: 2000}}
kinematics:
  joints:
    yaw:   {type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, 0.1]}, channel: base}
    lift:  {type: revolute, parent: yaw, axis: [0, -1, 0], origin: {xyz: [0, 0, 0.05]}, channel: shoulder}
    bend:  {type: revolute, parent: lift, axis: [0, -1, 0], origin: {xyz: [0.2, 0, 0]}, channel: elbow}
  effectors:
    hand: {joint: bend, origin: {xyz: [0.2, 0, 0]}}
)";

/// A performer's hand circling 5 cm around a point 40 cm in front of the hips (centimetres, Y up,
/// Z forward), 2 s at 30 fps.
std::string bake_hand_circle_bvh() {
  std::ostringstream bvh;
  bvh << "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
         "  JOINT RightHand\n  {\n    OFFSET 0 0 0\n    CHANNELS 3 Xposition Yposition Zposition\n"
         "    End Site\n    {\n      OFFSET 0 0 5\n    }\n  }\n}\nMOTION\nFrames: 61\nFrame Time: 0.0333333333\n";
  for (int i = 0; i <= 60; ++i) {
    const double a = 2 * std::numbers::pi * i / 60.0;
    bvh << "0 100 0 0 0 0 " << 5 * std::sin(a) << ' ' << 5 * std::cos(a) << " 40\n";
  }
  return bvh.str();
}

TEST(MocapBake, AHandPositionDrivesAnIkTargetThatThePlayedArmReaches) {
  const std::string rig = avar::testing::write_temp_file("arm.yaml", kBakeArmRig);
  const std::string bvh = avar::testing::write_temp_file("hand.bvh", bake_hand_circle_bvh());
  // File x (performer's left) -> rig y, file y (up) -> rig z, file z (forward) -> rig x; 40 cm
  // forward and level with the hips lands 0.28 m forward at 0.2 m up on the rig.
  const std::string map = avar::testing::write_temp_file(
      "map.yaml",
      "retarget:\n  source_units: 0.01\n  positions:\n    - {joint: RightHand, target: hand, origin: Hips, axes: [z, x, y], "
      "scale: 0.7, offset: [0, 0, 0.2]}\n");
  const std::string out = avar::testing::temp_path("hand.yaml");
  const testing::CliResult bake = testing::run_avar(
      {"mocap", "bake", bvh, "--map", map, "--rig", rig, "--out", out, "--position-tolerance", "0.0005", "--no-progress"});
  ASSERT_EQ(bake.code, kExitOk) << bake.err << bake.out;
  EXPECT_NE(bake.out.find("1 IK targets"), std::string::npos) << bake.out;
  const playback::Show show = config::load_show_file(out);
  ASSERT_EQ(show.targets.size(), 1u);
  EXPECT_EQ(show.targets[0].effector, "hand");
  // Relative to the hips the hand is (5 sin a, 5 cos a, 40) cm; in the rig, times 0.007 m/cm:
  // (0.28, 0.035 sin a, 0.2 + 0.035 cos a). A quarter turn at 0.5 s, none at 0.
  const auto& xyz = show.targets[0].xyz;
  EXPECT_NEAR(xyz[0].evaluate(0.5), 0.28, 5e-4);
  EXPECT_NEAR(xyz[1].evaluate(0.5), 0.035, 5e-4);
  EXPECT_NEAR(xyz[2].evaluate(0.5), 0.2, 5e-4);
  EXPECT_NEAR(xyz[1].evaluate(0), 0, 5e-4);
  EXPECT_NEAR(xyz[2].evaluate(0), 0.2 + 0.035, 5e-4);

  const testing::CliResult play =
      testing::run_avar({"play", bvh, "--map", map, "--rig", rig, "--sim", "--fast", "--no-progress"});
  ASSERT_EQ(play.code, kExitOk) << play.err << play.out;
  EXPECT_NE(play.out.find(" 0 degraded (target out of reach: closest pose used), 0 failed"), std::string::npos) << play.out;
  // The IK's position tolerance is 1e-5 m per component: the worst residual stays within it.
  const auto at = play.out.find("worst residual ");
  ASSERT_NE(at, std::string::npos) << play.out;
  EXPECT_LE(std::stod(play.out.substr(at + 15)), 0.01 * std::sqrt(3.0)) << play.out;
}

}  // namespace
}  // namespace avar::app
