// Inverse kinematics as a stage of the tick: the show's target tracks become channel targets for
// the joints on the goals' paths, warm-started tick to tick, within the channels' limits.
#include "avar/control/ik_stage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/kinematics/model_builder.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

/// A head: pan (about z) then tilt (about y), the gaze looking along x from 5 cm in front of the
/// tilt axis; a jaw on its own joint, not on the gaze's path.
Rig head_rig() {
  Rig r;
  r.name = "head";
  for (auto [name, lo, hi] : {std::tuple{"pan", -80.0, 80.0}, {"tilt", -30.0, 40.0}, {"jaw", 0.0, 30.0}})
    r.channels.push_back({.name = name, .unit = "deg", .min = lo, .max = hi, .rest = 0, .max_velocity = 300,
                          .max_acceleration = 3000, .max_jerk = 60000, .ramp_velocity = 60, .where = {}});
  kinematics::ModelBuilder b;
  kinematics::JointSpec pan{"pan", kinematics::JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -80 * kDeg, 80 * kDeg};
  pan.origin.translation() = Eigen::Vector3d(0, 0, 0.2);
  kinematics::JointSpec tilt{"tilt", kinematics::JointType::revolute, "pan", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitY(), -30 * kDeg, 40 * kDeg};
  kinematics::JointSpec jaw{"jaw", kinematics::JointType::revolute, "tilt", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitY(), 0, 30 * kDeg};
  b.add_joint(pan);
  b.add_joint(tilt);
  b.add_joint(jaw);
  Eigen::Isometry3d eye = Eigen::Isometry3d::Identity();
  eye.translation() = Eigen::Vector3d(0.05, 0, 0);
  b.add_effector({"gaze", "tilt", eye});
  RigKinematics k{b.build(), {{0, 0, kDeg, 0}, {1, 1, kDeg, 0}, {2, 2, kDeg, 0}}, {}, {}};
  r.kinematics = std::move(k);
  return r;
}

playback::Curve constant(double v, playback::RawCurve& raw) {
  playback::RawKey k;
  k.value = v;
  raw.keys = {k};
  return playback::Curve::build(raw);
}

playback::Show look_at(double x, double y, double z) {
  playback::Show s;
  s.name = "look";
  s.duration = 2;
  playback::TargetTrack t;
  t.effector = "gaze";
  t.kind = playback::TargetKind::aim;
  const double p[3] = {x, y, z};
  for (std::size_t i = 0; i < 3; ++i) t.xyz[i] = constant(p[i], t.raw[i]);
  s.targets.push_back(std::move(t));
  playback::Track jaw;
  jaw.channel = "jaw";
  jaw.curve = constant(12, jaw.raw);
  s.tracks.push_back(std::move(jaw));
  return s;
}

TEST(IkStage, AimsTheGazeAtATargetAndLeavesChannelsOffThePathToTheirTracks) {
  const Rig rig = head_rig();
  const playback::Show show = look_at(1.0, 1.0, 0.2 + 0.5);  // 45° left, up
  IkStage stage(*rig.kinematics, show, rig.rest_frame());
  EXPECT_EQ(std::vector<std::size_t>(stage.driven_channels().begin(), stage.driven_channels().end()),
            (std::vector<std::size_t>{0, 1}));
  std::vector<double> frame{0, 0, 12};
  const kinematics::IkResult r = stage.apply(0.5, frame);
  EXPECT_EQ(r.status, kinematics::IkStatus::converged);
  EXPECT_NEAR(frame[0], 45, 0.01);  // pan toward +y
  EXPECT_LT(frame[1], -10);         // tilt about +y: negative is up
  EXPECT_DOUBLE_EQ(frame[2], 12);   // the jaw keeps its track
  EXPECT_EQ(stage.stats().converged, 1u);
}

TEST(IkStage, AnUnreachableAimStaysWithinTheChannelLimitsAndIsDegraded) {
  const Rig rig = head_rig();
  const playback::Show show = look_at(0.2, 0.0, 5.0);  // nearly straight up: tilt would need -88°
  IkStage stage(*rig.kinematics, show, rig.rest_frame());
  std::vector<double> frame{0, 0, 0};
  const kinematics::IkResult r = stage.apply(0, frame);
  EXPECT_EQ(r.status, kinematics::IkStatus::degraded);
  EXPECT_GE(frame[1], -30 - 1e-9);  // at its limit, not past it
  EXPECT_NEAR(frame[1], -30, 1e-6);
  EXPECT_EQ(stage.stats().degraded, 1u);
}

TEST(IkStage, AnOrientationTargetTurnsTheHeadAndAPoseTargetPlacesTheHand) {
  const Rig rig = head_rig();
  playback::Show show;
  show.name = "turn";
  show.duration = 1;
  playback::TargetTrack t;
  t.effector = "gaze";
  t.kind = playback::TargetKind::orientation;
  const double rpy[3] = {0, -20 * kDeg, 30 * kDeg};  // pitch -20° about y: the gaze tilts up; yaw 30°: left
  for (std::size_t i = 0; i < 3; ++i) t.rpy[i] = constant(rpy[i], t.raw_rpy[i]);
  show.targets.push_back(std::move(t));
  IkStage stage(*rig.kinematics, show, rig.rest_frame());
  std::vector<double> frame{0, 0, 0};
  const kinematics::IkResult r = stage.apply(0, frame);
  EXPECT_EQ(r.status, kinematics::IkStatus::converged);
  EXPECT_NEAR(frame[0], 30, 1e-3);
  EXPECT_NEAR(frame[1], -20, 1e-3);
}

TEST(IkStage, FollowsAPathTargetAndOrientationKeys) {
  const Rig rig = head_rig();
  playback::Show show;
  show.name = "path";
  show.duration = 2;
  playback::TargetTrack t;
  t.effector = "gaze";
  t.kind = playback::TargetKind::aim;
  playback::PathSpec path;
  path.points = {{1, -0.5, 0.2}, {1, 0.5, 0.2}};
  path.spline = playback::PathSpline::linear;
  path.from = 0;
  path.to = 1;
  t.path.emplace(path);
  show.targets.push_back(std::move(t));
  IkStage stage(*rig.kinematics, show, rig.rest_frame());
  std::vector<double> frame{0, 0, 0};
  for (const double time : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5}) {
    EXPECT_EQ(stage.apply(time, frame).status, kinematics::IkStatus::converged) << time;
    const double y = std::clamp(-0.5 + time, -0.5, 0.5);  // constant speed, then the end holds
    EXPECT_NEAR(frame[0], std::atan2(y, 1.0) / kDeg, 1e-3) << time;
    EXPECT_NEAR(frame[1], 0, 1e-3) << time;
  }

  playback::Show turn;
  turn.name = "turn";
  turn.duration = 2;
  playback::TargetTrack o;
  o.effector = "gaze";
  o.kind = playback::TargetKind::orientation;
  playback::OrientationKeysSpec keys;
  playback::OrientationKeySpec first, second;
  first.euler = {0, -20 * kDeg, 30 * kDeg};  // as the roll, pitch, yaw test: tilt up 20°, pan left 30°
  second.time = 2;
  second.quaternion = Eigen::Quaterniond::Identity();
  keys.keys = {first, second};
  o.orientation_keys.emplace(keys);
  turn.targets.push_back(std::move(o));
  IkStage turning(*rig.kinematics, turn, rig.rest_frame());
  EXPECT_EQ(turning.apply(0, frame).status, kinematics::IkStatus::converged);
  EXPECT_NEAR(frame[0], 30, 1e-3);
  EXPECT_NEAR(frame[1], -20, 1e-3);
  EXPECT_EQ(turning.apply(2, frame).status, kinematics::IkStatus::converged);
  EXPECT_NEAR(frame[0], 0, 1e-3);
  EXPECT_NEAR(frame[1], 0, 1e-3);
}

TEST(IkStage, TheControllerHomesToTheSolvedPoseAndPlaysIt) {
  const Rig rig = head_rig();
  const playback::Show show = look_at(1.0, -0.5, 0.2);
  struct NullLink final : firmware_iface::ActuatorLink {
    Status start() override { return Status::ok; }
    Status read_positions(std::span<double>, std::span<bool>) override { return Status::ok; }
    Status send(std::span<const double>) noexcept override { return Status::ok; }
    Status release() noexcept override { return Status::ok; }
    void release_channel(std::size_t) noexcept override {}
    std::uint64_t saturated_pulses() const noexcept override { return 0; }
    const std::string& describe() const noexcept override { return name; }
    std::string name = "null";
  } link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  ASSERT_NE(c.ik(), nullptr);
  c.begin(0, rig.rest_frame());
  for (int k = 0; k < 150; ++k) c.tick(k * 0.01);
  EXPECT_EQ(c.phase(), Phase::running);
  EXPECT_NEAR(c.commanded()[0], std::atan2(-0.5, 1.0) / kDeg, 0.01);
  EXPECT_NEAR(c.commanded()[1], 0, 0.01);
  EXPECT_NEAR(c.commanded()[2], 12, 1e-9);
  EXPECT_GT(c.ik()->stats().converged, 50u);
  EXPECT_EQ(c.ik()->stats().failed, 0u);
}

}  // namespace
}  // namespace avar::control
