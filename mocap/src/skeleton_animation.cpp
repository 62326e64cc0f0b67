#include "avar/mocap/skeleton_animation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace avar::mocap {
namespace {

bool finite_vector(const Eigen::Vector3d& v) { return v.allFinite(); }

template <typename... Parts>
std::string model_message(const Parts&... parts) {
  std::ostringstream text;
  (text << ... << parts);
  return text.str();
}

void check_pose(const Pose& pose, std::size_t joints, std::size_t frame) {
  if (pose.translation.size() != joints || pose.rotation.size() != joints || pose.scale.size() != joints) {
    throw std::invalid_argument(model_message("frame ", frame, " holds ", pose.rotation.size(), " joint rotations, ",
                                              pose.translation.size(), " translations and ", pose.scale.size(),
                                              " scales; the skeleton has ", joints, " joints"));
  }
  for (std::size_t j = 0; j < joints; ++j) {
    const double norm = pose.rotation[j].norm();
    if (!finite_vector(pose.translation[j]) || !finite_vector(pose.scale[j]) || !std::isfinite(norm) ||
        std::abs(norm - 1.0) > 1e-6) {
      throw std::invalid_argument(
          model_message("frame ", frame, ", joint ", j, ": transform is not finite or rotation not unit"));
    }
  }
}

}  // namespace

double SkeletonAnimation::duration() const noexcept {
  return frames.empty() ? 0.0 : static_cast<double>(frames.size() - 1) * frame_time;
}

std::optional<std::size_t> SkeletonAnimation::find_joint(std::string_view name) const noexcept {
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].name == name) return j;
  }
  return std::nullopt;
}

Pose rest_pose(const SkeletonAnimation& animation) {
  Pose pose;
  pose.translation.reserve(animation.joints.size());
  pose.rotation.reserve(animation.joints.size());
  pose.scale.reserve(animation.joints.size());
  for (const Joint& joint : animation.joints) {
    pose.translation.push_back(joint.rest_translation);
    pose.rotation.push_back(joint.rest_rotation);
    pose.scale.push_back(joint.rest_scale);
  }
  return pose;
}

void validate(const SkeletonAnimation& animation) {
  if (animation.joints.empty()) throw std::invalid_argument("the skeleton has no joints");
  if (!(animation.frame_time > 0) || !std::isfinite(animation.frame_time)) {
    throw std::invalid_argument(model_message("frame time ", animation.frame_time, " s is not a positive number"));
  }
  if (animation.frames.empty()) throw std::invalid_argument("the animation has no frames");
  if (!animation.channels.empty() && animation.channels.size() != animation.joints.size()) {
    throw std::invalid_argument(
        model_message("channels describe ", animation.channels.size(), " joints; the skeleton has ", animation.joints.size()));
  }
  for (std::size_t j = 0; j < animation.joints.size(); ++j) {
    const std::ptrdiff_t parent = animation.joints[j].parent;
    if (parent != kNoParent && (parent < 0 || static_cast<std::size_t>(parent) >= j)) {
      throw std::invalid_argument(
          model_message("joint '", animation.joints[j].name, "' has parent ", parent, ", which does not precede it"));
    }
  }
  for (std::size_t f = 0; f < animation.frames.size(); ++f) check_pose(animation.frames[f], animation.joints.size(), f);
}

void evaluate(const SkeletonAnimation& animation, double t, Pose& out) {
  const std::size_t joints = animation.joints.size();
  out.translation.resize(joints);
  out.rotation.resize(joints);
  out.scale.resize(joints);
  const std::size_t last = animation.frames.size() - 1;
  const double position = std::clamp(t / animation.frame_time, 0.0, static_cast<double>(last));
  const auto i = std::min(static_cast<std::size_t>(position), last);
  const std::size_t k = std::min(i + 1, last);
  const double u = position - static_cast<double>(i);
  const Pose& a = animation.frames[i];
  const Pose& b = animation.frames[k];
  for (std::size_t j = 0; j < joints; ++j) {
    out.translation[j] = a.translation[j] + u * (b.translation[j] - a.translation[j]);
    out.scale[j] = a.scale[j] + u * (b.scale[j] - a.scale[j]);
    out.rotation[j] = a.rotation[j].slerp(u, b.rotation[j]).normalized();
  }
}

void forward_kinematics(const SkeletonAnimation& animation, const Pose& pose, std::vector<Eigen::Affine3d>& world) {
  const std::size_t joints = animation.joints.size();
  world.resize(joints);
  for (std::size_t j = 0; j < joints; ++j) {
    Eigen::Affine3d local = Eigen::Affine3d::Identity();
    local.translate(pose.translation[j]);
    local.rotate(pose.rotation[j]);
    local.scale(pose.scale[j]);
    const std::ptrdiff_t parent = animation.joints[j].parent;
    world[j] = parent == kNoParent ? local : world[static_cast<std::size_t>(parent)] * local;
  }
}

void align_hemispheres(SkeletonAnimation& animation) noexcept {
  for (std::size_t f = 1; f < animation.frames.size(); ++f) {
    const Pose& previous = animation.frames[f - 1];
    Pose& current = animation.frames[f];
    for (std::size_t j = 0; j < current.rotation.size(); ++j) {
      if (previous.rotation[j].dot(current.rotation[j]) < 0) current.rotation[j].coeffs() *= -1.0;
    }
  }
}

}  // namespace avar::mocap
