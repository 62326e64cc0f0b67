#include "avar/mocap/skeleton_animation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace avar::mocap {
namespace {

// Two joints: a root at (0, 0, 1) and a child 2 units along the root's x axis.
SkeletonAnimation two_joint_arm() {
  SkeletonAnimation animation;
  animation.source = "arm";
  animation.joints = {Joint{"root", kNoParent, {0, 0, 1}, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Ones(), false},
                      Joint{"hand", 0, {2, 0, 0}, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Ones(), true}};
  animation.frame_time = 0.5;
  Pose first = rest_pose(animation);
  Pose second = first;
  second.rotation[0] = Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  animation.frames = {first, second};
  return animation;
}

TEST(SkeletonAnimationModel, ForwardKinematicsComposesParentThenLocal) {
  const SkeletonAnimation animation = two_joint_arm();
  std::vector<Eigen::Affine3d> world;
  forward_kinematics(animation, animation.frames[1], world);
  // The root turned 90 degrees about z carries the hand from +x to +y.
  EXPECT_NEAR((world[1].translation() - Eigen::Vector3d(0, 2, 1)).norm(), 0, 1e-12);
}

TEST(SkeletonAnimationModel, EvaluatesBySlerpBetweenFramesAndClamps) {
  const SkeletonAnimation animation = two_joint_arm();
  Pose pose;
  std::vector<Eigen::Affine3d> world;
  evaluate(animation, 0.25, pose);  // halfway: 45 degrees
  forward_kinematics(animation, pose, world);
  EXPECT_NEAR((world[1].translation() - Eigen::Vector3d(std::sqrt(2.0), std::sqrt(2.0), 1)).norm(), 0, 1e-12);
  evaluate(animation, 7.0, pose);
  EXPECT_TRUE(pose.rotation[0].isApprox(animation.frames[1].rotation[0]));
  evaluate(animation, -1.0, pose);
  EXPECT_TRUE(pose.rotation[0].isApprox(Eigen::Quaterniond::Identity()));
  EXPECT_DOUBLE_EQ(animation.duration(), 0.5);
  EXPECT_EQ(animation.find_joint("hand"), 1U);
  EXPECT_FALSE(animation.find_joint("foot"));
}

TEST(SkeletonAnimationModel, AlignsHemispheresSoSlerpTurnsTheShortWay) {
  SkeletonAnimation animation = two_joint_arm();
  animation.frames[1].rotation[0].coeffs() *= -1.0;
  align_hemispheres(animation);
  EXPECT_GT(animation.frames[0].rotation[0].dot(animation.frames[1].rotation[0]), 0);
}

TEST(SkeletonAnimationModel, ValidateRefusesBrokenModels) {
  SkeletonAnimation parent_after = two_joint_arm();
  parent_after.joints[0].parent = 1;
  EXPECT_THROW(validate(parent_after), std::invalid_argument);
  SkeletonAnimation short_frame = two_joint_arm();
  short_frame.frames[1].rotation.pop_back();
  EXPECT_THROW(validate(short_frame), std::invalid_argument);
  SkeletonAnimation nan_offset = two_joint_arm();
  nan_offset.frames[0].translation[1].x() = std::nan("");
  EXPECT_THROW(validate(nan_offset), std::invalid_argument);
  SkeletonAnimation no_time = two_joint_arm();
  no_time.frame_time = 0;
  EXPECT_THROW(validate(no_time), std::invalid_argument);
  EXPECT_NO_THROW(validate(two_joint_arm()));
}

}  // namespace
}  // namespace avar::mocap
