// Retargeting maths: a joint's rotation about one Euler axis onto a channel (several orders,
// rest or first-frame reference, scale, offset, reversal, unwrapping) and a joint's position onto
// an IK target (origin joint, axis mapping, units), against hand-computed values.
#include "avar/mocap/retarget.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace avar::mocap {
namespace {

constexpr double kRetargetDeg = std::numbers::pi / 180;

Eigen::Quaterniond retarget_about(double degrees, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kRetargetDeg, axis));
}

/// A root at the origin and a child 10 file units along x, every frame at rest; `frames` frames
/// 0.1 s apart.
SkeletonAnimation retarget_arm(std::size_t frames) {
  SkeletonAnimation a;
  a.source = "arm.bvh";
  a.joints = {Joint{"Hips", kNoParent, {0, 0, 0}, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Ones(), false},
              Joint{"Hand", 0, {10, 0, 0}, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Ones(), false}};
  a.frame_time = 0.1;
  a.frames.assign(frames, rest_pose(a));
  return a;
}

RotationBinding retarget_binding(int axis, playback::EulerOrder order) {
  RotationBinding b;
  b.joint = "Hand";
  b.channel = "neck";
  b.axis = axis;
  b.order = order;
  b.joint_where = {"map.yaml", 4, 14};
  return b;
}

TEST(RetargetRotation, PicksTheStatedAngleOfTheStatedOrder) {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  // Order "abc" is R = Rc Rb Ra (fixed axes): built by hand from angle-axis rotations.
  const Eigen::Quaterniond zxy = retarget_about(20, y) * retarget_about(10, x) * retarget_about(30, z);
  EXPECT_NEAR(rotation_value(retarget_binding(0, playback::EulerOrder::zxy), zxy), 10, 1e-9);
  EXPECT_NEAR(rotation_value(retarget_binding(1, playback::EulerOrder::zxy), zxy), 20, 1e-9);
  EXPECT_NEAR(rotation_value(retarget_binding(2, playback::EulerOrder::zxy), zxy), 30, 1e-9);
  const Eigen::Quaterniond xyz = retarget_about(-40, z) * retarget_about(15, y) * retarget_about(25, x);
  EXPECT_NEAR(rotation_value(retarget_binding(0, playback::EulerOrder::xyz), xyz), 25, 1e-9);
  EXPECT_NEAR(rotation_value(retarget_binding(1, playback::EulerOrder::xyz), xyz), 15, 1e-9);
  EXPECT_NEAR(rotation_value(retarget_binding(2, playback::EulerOrder::xyz), xyz), -40, 1e-9);
  const Eigen::Quaterniond yzx = retarget_about(5, x) * retarget_about(-35, z) * retarget_about(60, y);
  EXPECT_NEAR(rotation_value(retarget_binding(1, playback::EulerOrder::yzx), yzx), 60, 1e-9);
  EXPECT_NEAR(rotation_value(retarget_binding(2, playback::EulerOrder::yzx), yzx), -35, 1e-9);
  // The same rotation read in another order gives other angles: the order matters.
  EXPECT_GT(std::abs(rotation_value(retarget_binding(1, playback::EulerOrder::xyz), zxy) - 20), 0.5);
}

TEST(RetargetRotation, AppliesScaleReversalOffsetAndUnits) {
  RotationBinding b = retarget_binding(1, playback::EulerOrder::zxy);
  const Eigen::Quaterniond q = retarget_about(30, Eigen::Vector3d::UnitY());
  b.scale = 2;
  b.offset = 5;
  EXPECT_NEAR(rotation_value(b, q), 65, 1e-9);  // 2 * 30 + 5
  b.reverse = true;
  EXPECT_NEAR(rotation_value(b, q), -55, 1e-9);  // -(2 * 30) + 5
  b.units = AngleUnit::rad;
  EXPECT_NEAR(rotation_value(b, q), -2 * std::numbers::pi / 6 + 5, 1e-12);
}

TEST(RetargetRotation, MeasuresFromRestOrFromTheFirstFrameAndUnwraps) {
  SkeletonAnimation a = retarget_arm(3);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  a.joints[1].rest_rotation = retarget_about(90, z);
  a.frames[0].rotation[1] = retarget_about(90 + 10, z);
  a.frames[1].rotation[1] = retarget_about(90 + 170, z);
  a.frames[2].rotation[1] = retarget_about(90 + 200, z);  // past 180: keeps going
  align_hemispheres(a);
  RetargetMap map;
  map.rotations = {retarget_binding(2, playback::EulerOrder::xyz), retarget_binding(2, playback::EulerOrder::xyz)};
  map.rotations[1].relative_to = RelativeTo::first_frame;
  map.rotations[1].channel = "other";
  const RetargetedMotion m = retarget(a, map, 10);
  ASSERT_EQ(m.times.size(), 3u);
  EXPECT_NEAR(m.times[2], 0.2, 1e-12);
  ASSERT_EQ(m.channels.size(), 2u);
  EXPECT_EQ(m.channels[1].channel, "other");
  EXPECT_NEAR(m.channels[0].values[0], 10, 1e-9);
  EXPECT_NEAR(m.channels[0].values[1], 170, 1e-9);
  EXPECT_NEAR(m.channels[0].values[2], 200, 1e-9);
  EXPECT_NEAR(m.channels[1].values[0], 0, 1e-9);
  EXPECT_NEAR(m.channels[1].values[2], 190, 1e-9);
}

TEST(RetargetRotation, SamplesBetweenFramesBySlerpAtTheAskedRate) {
  SkeletonAnimation a = retarget_arm(2);
  a.frames[1].rotation[1] = retarget_about(40, Eigen::Vector3d::UnitX());
  RetargetMap map;
  map.rotations = {retarget_binding(0, playback::EulerOrder::zyx)};
  const RetargetedMotion m = retarget(a, map, 40);  // 0, 0.025, ..., 0.1
  ASSERT_EQ(m.times.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(m.channels[0].values[i], 10.0 * static_cast<double>(i), 1e-9) << i;
}

TEST(RetargetPosition, MapsAJointPositionFromItsOriginIntoRigAxesAndMetres) {
  SkeletonAnimation a = retarget_arm(2);
  a.frames[0].translation[0] = {5, 5, 5};  // the origin joint moves with the hand: no change
  a.frames[1].translation[0] = {5, 5, 5};
  a.frames[1].rotation[0] = retarget_about(90, Eigen::Vector3d::UnitZ());  // hand from +x to +y
  RetargetMap map;
  map.source_units = 0.01;  // centimetres
  PositionBinding b;
  b.joint = "Hand";
  b.target = "hand";
  b.origin = "Hips";
  b.from = {0, 2, 1};  // axes: [x, -z, y]
  b.sign = {1, -1, 1};
  b.scale = 2;
  b.offset = {0.3, 0, 0.1};
  map.positions = {b};
  const RetargetedMotion m = retarget(a, map, 10);
  ASSERT_EQ(m.targets.size(), 1u);
  const auto& t = m.targets[0];
  // Frame 0: hand 10 cm along file x -> rig x 0.2 m (scale 2) + 0.3.
  EXPECT_NEAR(t.xyz[0][0], 0.5, 1e-12);
  EXPECT_NEAR(t.xyz[1][0], 0, 1e-12);
  EXPECT_NEAR(t.xyz[2][0], 0.1, 1e-12);
  // Frame 1: hand 10 cm along file y -> rig z (0.2 m) + 0.1.
  EXPECT_NEAR(t.xyz[0][1], 0.3, 1e-12);
  EXPECT_NEAR(t.xyz[1][1], 0, 1e-12);
  EXPECT_NEAR(t.xyz[2][1], 0.3, 1e-12);
}

TEST(RetargetNames, UnknownJointIsRefusedAtItsPlaceInTheMap) {
  const SkeletonAnimation a = retarget_arm(2);
  RetargetMap map;
  map.rotations = {retarget_binding(0, playback::EulerOrder::xyz)};
  map.rotations[0].joint = "Head";
  try {
    (void)retarget(a, map, 10);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "map.yaml:4:14: unknown joint 'Head' in arm.bvh; expected one of its joints: Hips, Hand");
  }
  PositionBinding p;
  p.joint = "Hand";
  p.origin = "Root";
  p.origin_where = {"map.yaml", 9, 15};
  map.rotations.clear();
  map.positions = {p};
  try {
    (void)retarget(a, map, 10);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 9);
    EXPECT_NE(std::string(e.what()).find("unknown joint 'Root'"), std::string::npos);
  }
}

}  // namespace
}  // namespace avar::mocap
