#include "avar/control/gaze_look_at.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/ik_options.hpp"
#include "avar/kinematics/ik_solver.hpp"
#include "avar/kinematics/model_builder.hpp"

namespace avar::control {
namespace {

static_assert(playback::GazeLookAt::kOnBase == kinematics::Joint::kNoParent);

Eigen::Vector3d gaze_look_at_vector(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

/// The eyes' own joints (every joint between an eye effector and the mount) as a model of their
/// own whose base is the mount's frame, with the eye effectors in spec order. Each movable
/// joint's range is its channel's inside the soft margins (and the figure's joint limits).
kinematics::Model gaze_look_at_eye_model(const kinematics::Model& figure, const std::vector<rig::JointBinding>& bindings,
                                         const playback::GazeLookAt& spec, std::span<const playback::IdleChannelLimits> limits,
                                         std::vector<rig::JointBinding>& eye_bindings) {
  std::vector<char> own(figure.joint_count(), 0);
  for (const std::size_t e : spec.effectors) {
    if (e >= figure.effector_count())
      throw std::invalid_argument("look-at gaze: no effector " + std::to_string(e) + " in the model");
    for (std::size_t j = figure.effector(e).joint; j != spec.mount_joint; j = figure.joint(j).parent) {
      if (j == kinematics::Joint::kNoParent)
        throw std::invalid_argument("look-at gaze: effector '" + figure.effector(e).name +
                                    "' does not hang from the eyes' mount");
      own[j] = 1;
    }
  }
  kinematics::ModelBuilder builder;
  for (std::size_t j = 0; j < figure.joint_count(); ++j) {
    if (!own[j]) continue;
    const kinematics::Joint& joint = figure.joint(j);
    kinematics::JointSpec js;
    js.name = joint.name;
    js.type = joint.type;
    js.parent = joint.parent == spec.mount_joint ? std::string() : figure.joint(joint.parent).name;
    js.origin = joint.origin;
    js.axis = joint.movable() ? joint.axis : Eigen::Vector3d::UnitZ();
    if (joint.movable()) {
      rig::JointBinding b = bindings.at(joint.q_index);
      if (b.channel >= limits.size())
        throw std::invalid_argument("look-at gaze: joint '" + joint.name + "' drives no channel of the frame");
      const double a = b.to_joint(limits[b.channel].low()), z = b.to_joint(limits[b.channel].high());
      js.lower = std::max(joint.lower, std::min(a, z));
      js.upper = std::min(joint.upper, std::max(a, z));
      if (js.lower > js.upper) js.lower = js.upper = std::clamp(b.to_joint(limits[b.channel].rest), joint.lower, joint.upper);
      b.q_index = eye_bindings.size();
      eye_bindings.push_back(b);
    }
    builder.add_joint(js);
  }
  for (const std::size_t e : spec.effectors) {
    const kinematics::Effector& eff = figure.effector(e);
    builder.add_effector({eff.name, figure.joint(eff.joint).name, eff.tool});
  }
  return builder.build();
}

}  // namespace

GazeLookAt::GazeLookAt(const rig::RigKinematics& kinematics, const playback::GazeLookAt& spec,
                       std::span<const playback::IdleChannelLimits> limits)
    : figure_(kinematics.model),
      bindings_(kinematics.bindings),
      eyes_(gaze_look_at_eye_model(kinematics.model, kinematics.bindings, spec, limits, eye_bindings_)),
      mount_(spec.mount_joint),
      centre_(gaze_look_at_vector(spec.centre)),
      ahead_(gaze_look_at_vector(spec.ahead)),
      left_(gaze_look_at_vector(spec.left)),
      up_(gaze_look_at_vector(spec.up)),
      figure_poses_(figure_),
      ik_(eyes_, std::max<std::size_t>(1, spec.effectors.size())),
      figure_q_(figure_.dof(), 0.0),
      q_(eyes_.dof(), 0.0),
      q_next_(eyes_.dof(), 0.0) {
  if (spec.effectors.empty()) throw std::invalid_argument("look-at gaze needs at least one eye effector");
  if (mount_ != playback::GazeLookAt::kOnBase && mount_ >= figure_.joint_count())
    throw std::invalid_argument("look-at gaze: no joint " + std::to_string(mount_) + " to hang the eyes from");
  for (const rig::JointBinding& b : bindings_)
    if (b.channel >= limits.size())
      throw std::invalid_argument("look-at gaze: the kinematics drive channels the frame does not have");
  const Eigen::Vector3d axis = gaze_look_at_vector(spec.aim_axis);
  for (std::size_t i = 0; i < spec.effectors.size(); ++i) goals_.push_back(kinematics::IkGoal::aiming(i, axis, centre_ + ahead_));
  // The first seed: the eyes at rest.
  for (const rig::JointBinding& b : eye_bindings_)
    q_[b.q_index] =
        std::clamp(b.to_joint(limits[b.channel].rest), eyes_.lower_limits()[b.q_index], eyes_.upper_limits()[b.q_index]);
}

Eigen::Vector3d GazeLookAt::world_point(const playback::GazePoint& point) const noexcept {
  const double pan = point.pan_deg * std::numbers::pi / 180, tilt = point.tilt_deg * std::numbers::pi / 180;
  const Eigen::Vector3d direction = std::cos(tilt) * (std::cos(pan) * ahead_ + std::sin(pan) * left_) + std::sin(tilt) * up_;
  return centre_ + point.distance_m * direction;
}

void GazeLookAt::aim(const playback::GazePoint& point, std::span<double> frame) noexcept {
  // The figure as the frame poses it, for the head's frame in the world.
  for (const rig::JointBinding& b : bindings_)
    figure_q_[b.q_index] =
        std::clamp(b.to_joint(frame[b.channel]), figure_.lower_limits()[b.q_index], figure_.upper_limits()[b.q_index]);
  if (kinematics::forward_kinematics(figure_, figure_q_, figure_poses_) != Status::ok) return;
  const Eigen::Isometry3d head =
      mount_ == playback::GazeLookAt::kOnBase ? Eigen::Isometry3d::Identity() : figure_poses_.joint_pose(mount_);
  const Eigen::Vector3d target = head.inverse(Eigen::Isometry) * world_point(point);
  if (!target.allFinite()) return;
  for (kinematics::IkGoal& goal : goals_) goal.position = target;
  const kinematics::IkOptions options = cold_ ? kinematics::cold_start_ik_options() : kinematics::default_ik_options();
  const kinematics::IkResult result = kinematics::solve_ik(eyes_, ik_, goals_, q_, q_next_, options);
  if (record_ik_outcome(stats_, result)) {
    std::copy(q_next_.begin(), q_next_.end(), q_.begin());
    cold_ = false;
  }
  for (const rig::JointBinding& b : eye_bindings_) frame[b.channel] = b.to_channel(q_[b.q_index]);
}

}  // namespace avar::control
