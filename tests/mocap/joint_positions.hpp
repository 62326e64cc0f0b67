#pragma once
// Mocap test helpers: the fixtures under tests/data/mocap and world positions of named joints.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "avar/mocap/skeleton_animation.hpp"

namespace avar::mocap::testing {

inline std::string mocap_fixture(const std::string& name) { return AVAR_SOURCE_DIR "/tests/data/mocap/" + name; }

/// World position of joint `name` at frame `frame` by the model's forward kinematics (NaN and a
/// failed expectation when there is no such joint).
inline Eigen::Vector3d joint_world(const SkeletonAnimation& animation, std::size_t frame, const std::string& name) {
  std::vector<Eigen::Affine3d> world;
  forward_kinematics(animation, animation.frames.at(frame), world);
  const auto joint = animation.find_joint(name);
  EXPECT_TRUE(joint) << name;
  if (!joint) return Eigen::Vector3d::Constant(std::nan(""));
  return world[*joint].translation();
}

}  // namespace avar::mocap::testing

/// Joint `joint` of `animation` at frame `frame` lies within `tolerance` of (x, y, z).
#define EXPECT_JOINT_AT(animation, frame, joint, x, y, z, tolerance)                                                     \
  EXPECT_LT((::avar::mocap::testing::joint_world(animation, frame, joint) - Eigen::Vector3d(x, y, z)).norm(), tolerance) \
      << "frame " << (frame) << " joint " << (joint) << " at "                                                           \
      << ::avar::mocap::testing::joint_world(animation, frame, joint).transpose()
