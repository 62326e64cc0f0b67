#pragma once
// What every mocap importer promises about an animation it returns (skeleton_animation.hpp): the
// fuzz targets abort when a returned animation breaks it.
#include <cmath>
#include <cstdlib>

#include "avar/mocap/skeleton_animation.hpp"

namespace avar::fuzz {

inline void check_skeleton_animation(const avar::mocap::SkeletonAnimation& animation) {
  const std::size_t joints = animation.joints.size();
  if (joints == 0 || !(animation.frame_time > 0) || !std::isfinite(animation.frame_time)) std::abort();
  if (!animation.channels.empty() && animation.channels.size() != joints) std::abort();
  for (std::size_t j = 0; j < joints; ++j) {
    const auto parent = animation.joints[j].parent;
    if (parent != avar::mocap::kNoParent && (parent < 0 || static_cast<std::size_t>(parent) >= j)) std::abort();
  }
  for (const auto& pose : animation.frames) {
    if (pose.translation.size() != joints || pose.rotation.size() != joints || pose.scale.size() != joints) std::abort();
    for (std::size_t j = 0; j < joints; ++j) {
      if (!pose.translation[j].allFinite() || !pose.scale[j].allFinite() || !pose.rotation[j].coeffs().allFinite()) std::abort();
      if (std::abs(pose.rotation[j].norm() - 1.0) > 1e-6) std::abort();
    }
  }
}

}  // namespace avar::fuzz
