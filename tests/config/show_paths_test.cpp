// Path targets, speed control and orientation keys in show files: they load, are checked against
// a rig, are rejected with file:line:column and what was expected when wrong, and survive a round
// trip through the show writer exactly.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/control/ik_stage.hpp"

namespace avar::config {
namespace {

std::string paths_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }
using avar::testing::replace;

const std::string kPathsShow = R"(duration: 6
targets:
  hand:
    path:
      points: [[0.3, 0, 0.2], [0.3, 0.1, 0.3], [0.2, 0.2, 0.3], [0.1, 0.2, 0.2]]
      spline: catmull_rom
      from: 1.0
      to: 4.0
      speed: {shape: sine_constant_middle, k1: 0.2, k2: 0.8}
      orient: {along: tangent, up: [0, 0, 1]}
  wrist:
    orientation_keys:
      order: zyx
      interpolation: squad
      keys:
        - {time: 0, euler: [0, 0, 0]}
        - {time: 2, quaternion: [0.7071067811865476, 0, 0, 0.7071067811865476]}
        - {time: 3, euler: [0.5, 0, 1.5]}
  eyes:
    aim: [1, 0, 0]
    path:
      points: [[1, -0.5, 0.3], [1, 0.5, 0.6]]
      spline: linear
      from: 0
      to: 6
      speed: [{time: 0, value: 0}, {time: 0.5, value: 0.2}, {time: 1, value: 1}]
)";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream all;
  all << in.rdbuf();
  return all.str();
}

playback::Show load(const std::string& text) { return load_show_file(avar::testing::write_temp_file("paths.yaml", text)); }

TEST(ShowPaths, PathTargetsAndOrientationKeysLoad) {
  const playback::Show show = load(kPathsShow);
  ASSERT_EQ(show.targets.size(), 3u);
  const playback::TargetTrack& hand = show.targets[0];
  EXPECT_EQ(hand.kind, playback::TargetKind::pose);
  ASSERT_TRUE(hand.path);
  EXPECT_EQ(hand.path->spec().orientation, playback::PathOrientation::tangent);
  EXPECT_TRUE(hand.path->sample(0).position.isApprox(Eigen::Vector3d(0.3, 0, 0.2), 1e-12));
  EXPECT_TRUE(hand.path->sample(5).position.isApprox(Eigen::Vector3d(0.1, 0.2, 0.2), 1e-12));
  EXPECT_NEAR(hand.path->sample(2.5).distance, 0.5 * hand.path->length(), 1e-9);
  const playback::TargetTrack& wrist = show.targets[1];
  EXPECT_EQ(wrist.kind, playback::TargetKind::orientation);
  ASSERT_TRUE(wrist.orientation_keys);
  EXPECT_LT(wrist.orientation_keys->evaluate(2).angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))), 1e-12);
  const playback::TargetTrack& eyes = show.targets[2];
  EXPECT_EQ(eyes.kind, playback::TargetKind::aim);
  EXPECT_EQ(eyes.path->spec().speed.shape(), playback::DistanceTimeShape::user);
  EXPECT_TRUE(eyes.path->sample(3).position.isApprox(Eigen::Vector3d(1, -0.5 + 0.2, 0.3 + 0.2 * 0.3), 1e-9));
}

TEST(ShowPaths, BadPathsAndKeysAreRejectedWithWhereAndWhat) {
  EXPECT_EQ(paths_error(replace(kPathsShow, "[[0.3, 0, 0.2], [0.3, 0.1, 0.3], [0.2, 0.2, 0.3], [0.1, 0.2, 0.2]]", "[[0.3, 0, 0.2]]")),
            ":5:15: expected the path of target 'hand' to have at least 2 points, found 1");
  EXPECT_EQ(paths_error(replace(kPathsShow, "[0.3, 0.1, 0.3]", "[0.3, 0.1]")),
            ":5:31: expected a point of the path of target 'hand' (m) to have 3 numbers [x, y, z], found 2");
  EXPECT_EQ(paths_error(replace(kPathsShow, "spline: catmull_rom", "spline: nurbs")),
            ":6:15: unknown path spline 'nurbs'; expected one of: linear, catmull_rom, cardinal, kochanek_bartels, bspline, bezier");
  EXPECT_EQ(paths_error(replace(kPathsShow, "to: 4.0", "to: 1.0")),
            ":8:11: expected the path's end time `to` (1 s) to come after its start time `from` (1 s)");
  EXPECT_EQ(paths_error(replace(kPathsShow, "to: 4.0", "to: 7.0")), ":8:11: path end time 7 s is outside the show, which runs from 0 to 6 s");
  EXPECT_EQ(paths_error(replace(kPathsShow, "shape: sine_constant_middle", "shape: smooth")),
            ":9:22: unknown speed shape 'smooth'; expected one of: linear, sine, sine_constant_middle, parabolic, cubic");
  EXPECT_EQ(paths_error(replace(kPathsShow, "k1: 0.2, k2: 0.8", "k1: 0.9, k2: 0.8")),
            ":9:14: expected 0 <= k1 <= k2 <= 1 (normalised times ending the ease in and starting the ease out) in the speed of "
            "target 'hand', found k1 0.9, k2 0.8");
  EXPECT_EQ(paths_error(replace(kPathsShow, "{time: 0.5, value: 0.2}", "{time: 0.5, value: -0.2}")),
            ":26:15: expected a user distance-time curve (normalised time -> normalised distance) to rise from 0 to 1 without "
            "ever going back, but between 0 and 0.5 it reaches -0.00078125 at 0.00195312 after 0");
  EXPECT_EQ(paths_error(replace(kPathsShow, "{time: 1, value: 1}]", "{time: 1, value: 0.9}]")),
            ":26:61: expected a user distance-time curve (normalised time -> normalised distance) to end with a key at time 1, "
            "value 1; found time 1, value 0.9");
  EXPECT_EQ(paths_error(replace(kPathsShow, "{time: 0.5, value: 0.2}", "{tim: 0.5, value: 0.2}")),
            ":26:37: unknown field 'tim' in a key of track 'eyes.speed'; expected one of: time, value, interpolation, left, right, "
            "left_type, right_type, easing, back, amplitude, period, in_slope, out_slope, tension, continuity, bias");
  EXPECT_EQ(paths_error(replace(kPathsShow, "along: tangent", "along: sideways")),
            ":10:23: unknown orientation along the path 'sideways'; expected one of: frenet, tangent, or a map {along: frenet | "
            "tangent, up: [x, y, z]} or {look_at: [x, y, z], up: [x, y, z]}");
  EXPECT_EQ(paths_error(replace(kPathsShow, "along: tangent", "along: frenet")),
            ":10:35: field 'up' does not belong to a Frenet frame (its axes come from the path's bending); expected it only with "
            "along: tangent or look_at");
  EXPECT_EQ(paths_error(replace(kPathsShow, "    aim: [1, 0, 0]\n", "    aim: [1, 0, 0]\n    point: [1, 0, 0]\n")),
            ":23:7: target 'eyes' has both a path and a point; expected one or the other");
  EXPECT_EQ(paths_error(replace(kPathsShow, "      orient: {along: tangent, up: [0, 0, 1]}\n",
                             "      orient: frenet\n    orientation_keys: {keys: [{time: 0, euler: [0, 0, 0]}]}\n")),
            ":11:23: target 'hand' has orientation_keys and a path that orients it; expected one or the other");
  EXPECT_EQ(paths_error(replace(kPathsShow, "interpolation: squad", "interpolation: bezier")),
            ":14:22: unknown orientation interpolation 'bezier'; expected one of: slerp, squad");
  EXPECT_EQ(paths_error(replace(kPathsShow, "order: zyx", "order: xyx")),
            ":13:14: unknown Euler order 'xyx'; expected one of: xyz, xzy, yxz, yzx, zxy, zyx");
  EXPECT_EQ(paths_error(replace(kPathsShow, "{time: 2, quaternion", "{time: 0, quaternion")),
            ":17:11: orientation key time 0 s does not come after the previous key's 0 s; expected strictly increasing times");
  EXPECT_EQ(paths_error(replace(kPathsShow, "quaternion: [0.7071067811865476, 0, 0, 0.7071067811865476]", "quaternion: [1, 0, 0]")),
            ":17:33: expected a quaternion [w, x, y, z] of 4 numbers, found 3");
  EXPECT_EQ(paths_error(replace(kPathsShow, "{time: 0, euler: [0, 0, 0]}", "{time: 0}")),
            ":16:11: expected an orientation key of target 'wrist' ({time, quaternion: [w, x, y, z]} or {time, euler: [x, y, z]}) "
            "to have either quaternion or euler, not neither");
}

/// The hand's path as a Bezier: handles on some points, automatic on the others.
const std::string kBezierShow = replace(replace(kPathsShow, "[[0.3, 0, 0.2], [0.3, 0.1, 0.3], [0.2, 0.2, 0.3], [0.1, 0.2, 0.2]]",
                                                "[[0.3, 0, 0.2], {at: [0.3, 0.1, 0.3], left: [0.31, 0.05, 0.28], right: [0.29, 0.15, 0.32]},\n"
                                                "               {at: [0.2, 0.2, 0.3], right: [0.17, 0.21, 0.29]}, [0.1, 0.2, 0.2]]"),
                                        "spline: catmull_rom", "spline: bezier");

TEST(ShowPaths, BezierPathsLoadWithHandlesAndAutomaticHandles) {
  const playback::Show show = load(kBezierShow);
  const playback::PathTrack& path = *show.targets[0].path;
  const playback::PathSpec& spec = path.spec();
  EXPECT_EQ(spec.spline, playback::PathSpline::bezier);
  ASSERT_EQ(spec.left.size(), 4u);
  ASSERT_EQ(spec.right.size(), 4u);
  EXPECT_FALSE(spec.left[0] || spec.right[0] || spec.left[2] || spec.left[3] || spec.right[3]);
  EXPECT_EQ(*spec.left[1], Eigen::Vector3d(0.31, 0.05, 0.28));
  EXPECT_EQ(*spec.right[2], Eigen::Vector3d(0.17, 0.21, 0.29));
  EXPECT_TRUE(path.position_at(1).isApprox(Eigen::Vector3d(0.3, 0.1, 0.3), 1e-14));
  EXPECT_TRUE(path.derivative_at(1).isApprox(3 * (Eigen::Vector3d(0.29, 0.15, 0.32) - Eigen::Vector3d(0.3, 0.1, 0.3)), 1e-12));
  EXPECT_TRUE(show.targets[0].path->sample(5).position.isApprox(Eigen::Vector3d(0.1, 0.2, 0.2), 1e-12));
  // Without any handle, the plain form gives automatic handles and no handle lists.
  const playback::Show plain = load(replace(kPathsShow, "spline: catmull_rom", "spline: bezier"));
  EXPECT_TRUE(plain.targets[0].path->spec().left.empty());
  EXPECT_TRUE(plain.targets[0].path->spec().right.empty());
}

TEST(ShowPaths, BadBezierPointsAreRejectedWithWhereAndWhat) {
  EXPECT_EQ(paths_error(replace(kBezierShow, "left: [0.31, 0.05, 0.28]", "left: [0.31, .nan, 0.28]")),
            ":5:66: expected y of the left handle of a point of the path of target 'hand' (m) to be a finite number, found '.nan'");
  EXPECT_EQ(paths_error(replace(kBezierShow, "right: [0.17, 0.21, 0.29]", "right: [0.17, 0.21]")),
            ":6:45: expected the right handle of a point of the path of target 'hand' (m) to have 3 numbers [x, y, z], found 2");
  EXPECT_EQ(paths_error(replace(kBezierShow, "spline: bezier", "spline: catmull_rom")),
            ":5:59: field 'left' (a handle) does not belong to a catmull_rom path; expected handles only on bezier paths");
  EXPECT_EQ(paths_error(replace(kBezierShow, "{at: [0.2, 0.2, 0.3], right", "{right")),
            ":6:16: missing field 'at' in a point of the path of target 'hand' ({at: [x, y, z], left: [x, y, z], right: [x, y, z]})");
  EXPECT_EQ(paths_error(replace(kBezierShow, "{at: [0.2, 0.2, 0.3], right", "{at: [0.2, 0.2, 0.3], middle")),
            ":6:38: unknown field 'middle' in a point of the path of target 'hand'; expected one of: at, left, right");
}

TEST(ShowPaths, PathTargetsAndOrientationKeysSurviveAWriterRoundTripExactly) {
  for (const std::string& text : {kPathsShow, kBezierShow, replace(kBezierShow, "orient: {along: tangent, up: [0, 0, 1]}", "orient: frenet"),
                                  replace(kPathsShow, "orient: {along: tangent, up: [0, 0, 1]}", "orient: {look_at: [1, 0, 0]}"),
                                  replace(replace(kPathsShow, "orient: {along: tangent, up: [0, 0, 1]}", "orient: frenet"),
                                          "spline: catmull_rom", "spline: kochanek_bartels\n      tension: 0.2\n      bias: -0.3")}) {
    const playback::Show original = load(text);
    const std::string copy = avar::testing::temp_path("paths-copy.yaml");
    write_show_file(copy, original, "round trip");
    const playback::Show again = load_show_file(copy);
    ASSERT_EQ(again.targets.size(), original.targets.size());
    for (std::size_t i = 0; i < original.targets.size(); ++i) {
      const playback::TargetTrack& a = original.targets[i];
      const playback::TargetTrack& b = again.targets[i];
      EXPECT_EQ(a.kind, b.kind);
      EXPECT_EQ(a.path.has_value(), b.path.has_value());
      EXPECT_EQ(a.orientation_keys.has_value(), b.orientation_keys.has_value());
      for (double t = -0.5; t <= 6.5; t += 0.01) {
        if (a.path) {
          const playback::PathSample x = a.path->sample(t), y = b.path->sample(t);
          ASSERT_EQ(x.position, y.position) << a.effector << " at " << t;
          ASSERT_EQ(x.orientation.coeffs(), y.orientation.coeffs()) << a.effector << " at " << t;
        }
        if (a.orientation_keys) {
          ASSERT_EQ(a.orientation_keys->evaluate(t).coeffs(), b.orientation_keys->evaluate(t).coeffs()) << t;
        }
      }
    }
    // Written again, the file is the same text.
    const std::string twice = avar::testing::temp_path("paths-copy2.yaml");
    write_show_file(twice, again, "round trip");
    EXPECT_EQ(text_of(copy), text_of(twice));
  }
}

TEST(ShowPaths, TheExampleChecksAgainstItsRigAndUnknownEffectorsAreReported) {
  const rig::Rig rig = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml");
  const ShowCheck ok = check_show_against_rig(load_show_file(AVAR_SOURCE_DIR "/examples/shows/figure-eight.yaml"), rig);
  EXPECT_TRUE(ok.errors.empty()) << ok.errors.front().to_string();
  const ShowCheck bad = check_show_against_rig(load(kPathsShow), rig);
  ASSERT_EQ(bad.errors.size(), 2u);
  EXPECT_NE(bad.errors[0].to_string().find("unknown effector 'hand'; expected one of the rig's effectors: eyes"), std::string::npos);
}

TEST(ShowPaths, TheIkStageAimsTheGazeHeadAlongTheExamplePathEveryTick) {
  const rig::Rig rig = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml");
  const playback::Show show = load_show_file(AVAR_SOURCE_DIR "/examples/shows/figure-eight.yaml");
  control::IkStage stage(*rig.kinematics, show, rig.rest_frame());
  std::vector<double> frame = rig.rest_frame();
  const std::size_t pan = *rig.find_channel("neck_pan"), tilt = *rig.find_channel("neck_tilt");
  double least_pan = 0, most_pan = 0, least_tilt = 0, most_tilt = 0;
  for (double t = 0; t <= show.duration; t += 0.02) {
    const kinematics::IkResult r = stage.apply(t, frame);
    ASSERT_EQ(r.status, kinematics::IkStatus::converged) << t;
    ASSERT_LT(r.orientation_error, 1e-3) << t;  // the aim angle at the path's point
    least_pan = std::min(least_pan, frame[pan]);
    most_pan = std::max(most_pan, frame[pan]);
    least_tilt = std::min(least_tilt, frame[tilt]);
    most_tilt = std::max(most_tilt, frame[tilt]);
  }
  // The figure eight spans 0.5 m either side at 1 m: about 26.6 degrees of pan each way.
  EXPECT_NEAR(most_pan, 26.6, 0.5);
  EXPECT_NEAR(least_pan, -26.6, 0.5);
  EXPECT_LT(least_tilt, -2);  // up and down around the eyes' height
  EXPECT_GT(most_tilt, 2);
  EXPECT_EQ(stage.stats().failed, 0u);
}

}  // namespace
}  // namespace avar::config
