#include "avar/mocap/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace avar::mocap {
namespace {

std::size_t retarget_joint_index(const SkeletonAnimation& animation, const std::string& name, const SourceLocation& where) {
  if (const auto j = animation.find_joint(name)) return *j;
  std::string names;
  for (const Joint& joint : animation.joints)
    if (!joint.end_site) names += (names.empty() ? "" : ", ") + joint.name;
  throw InputError(where, "unknown joint '" + name + "' in " + (animation.source.empty() ? "the animation" : animation.source) +
                              "; expected one of its joints: " + names);
}

/// The sample times: every 1/rate seconds from 0, and the duration itself last.
std::vector<double> retarget_sample_times(double duration, double rate) {
  std::vector<double> times;
  const auto steps = static_cast<std::size_t>(std::floor(duration * rate + 1e-9));
  times.reserve(steps + 2);
  for (std::size_t i = 0; i <= steps; ++i) times.push_back(std::min(duration, static_cast<double>(i) / rate));
  if (duration - times.back() > 1e-9 / rate) times.push_back(duration);
  return times;
}

/// `angle` moved by whole turns to lie within half a turn of `previous`.
double retarget_unwrap(double angle, double previous) {
  constexpr double kTurn = 2 * std::numbers::pi;
  return angle + kTurn * std::round((previous - angle) / kTurn);
}

/// The channel value for an angle (radians) about the binding's axis.
double retarget_channel_value(const RotationBinding& b, double radians) noexcept {
  const double angle = b.units == AngleUnit::deg ? radians * 180 / std::numbers::pi : radians;
  return (b.reverse ? -1.0 : 1.0) * b.scale * angle + b.offset;
}

}  // namespace

double rotation_value(const RotationBinding& binding, const Eigen::Quaterniond& relative) noexcept {
  return retarget_channel_value(binding, playback::euler_from_quaternion(relative, binding.order)[binding.axis]);
}

Eigen::Vector3d position_value(const PositionBinding& binding, double source_units,
                               const Eigen::Vector3d& file_position) noexcept {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i)
    out[i] = binding.sign[static_cast<std::size_t>(i)] * file_position[binding.from[static_cast<std::size_t>(i)]] * source_units *
             binding.scale;
  return out + binding.offset;
}

RetargetedMotion retarget(const SkeletonAnimation& animation, const RetargetMap& map, double sample_rate_hz,
                          void (*progress)(double, void*), void* context) {
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) throw std::invalid_argument("retarget: sample rate must be > 0");
  if (animation.frames.empty()) throw std::invalid_argument("retarget: the animation has no frames");
  // Every name first: the map is checked whole before anything is computed.
  std::vector<std::size_t> rotation_joints, position_joints;
  std::vector<std::optional<std::size_t>> origins;
  for (const RotationBinding& b : map.rotations)
    rotation_joints.push_back(retarget_joint_index(animation, b.joint, b.joint_where));
  for (const PositionBinding& b : map.positions) {
    position_joints.push_back(retarget_joint_index(animation, b.joint, b.joint_where));
    origins.push_back(b.origin.empty() ? std::nullopt
                                       : std::optional<std::size_t>(retarget_joint_index(animation, b.origin, b.origin_where)));
  }

  RetargetedMotion motion;
  motion.times = retarget_sample_times(animation.duration(), sample_rate_hz);
  const std::size_t n = motion.times.size();
  for (std::size_t i = 0; i < map.rotations.size(); ++i) {
    motion.channels.push_back({map.rotations[i].channel, {}, i});
    motion.channels.back().values.reserve(n);
  }
  for (std::size_t i = 0; i < map.positions.size(); ++i) {
    motion.targets.push_back({map.positions[i].target, {}, i});
    for (auto& axis : motion.targets.back().xyz) axis.reserve(n);
  }

  // What each rotation is measured against: its rest rotation or its first frame's.
  std::vector<Eigen::Quaterniond> reference_inverse;
  for (std::size_t i = 0; i < map.rotations.size(); ++i) {
    const std::size_t j = rotation_joints[i];
    reference_inverse.push_back((map.rotations[i].relative_to == RelativeTo::rest ? animation.joints[j].rest_rotation
                                                                                  : animation.frames.front().rotation[j])
                                    .normalized()
                                    .conjugate());
  }

  Pose pose;
  std::vector<Eigen::Affine3d> world;
  std::vector<double> previous_radians(map.rotations.size(), 0);
  const std::size_t report_every = std::max<std::size_t>(1, n / 100);
  for (std::size_t s = 0; s < n; ++s) {
    evaluate(animation, motion.times[s], pose);
    for (std::size_t i = 0; i < map.rotations.size(); ++i) {
      const RotationBinding& b = map.rotations[i];
      const Eigen::Quaterniond relative = reference_inverse[i] * pose.rotation[rotation_joints[i]];
      double radians = playback::euler_from_quaternion(relative, b.order)[b.axis];
      if (s > 0) radians = retarget_unwrap(radians, previous_radians[i]);
      previous_radians[i] = radians;
      motion.channels[i].values.push_back(retarget_channel_value(b, radians));
    }
    if (!map.positions.empty()) {
      forward_kinematics(animation, pose, world);
      for (std::size_t i = 0; i < map.positions.size(); ++i) {
        Eigen::Vector3d p = world[position_joints[i]].translation();
        if (origins[i]) p -= world[*origins[i]].translation();
        const Eigen::Vector3d rig = position_value(map.positions[i], map.source_units, p);
        for (std::size_t a = 0; a < 3; ++a) motion.targets[i].xyz[a].push_back(rig[static_cast<Eigen::Index>(a)]);
      }
    }
    if (progress && (s % report_every == 0 || s + 1 == n)) progress(static_cast<double>(s + 1) / static_cast<double>(n), context);
  }
  return motion;
}

}  // namespace avar::mocap
