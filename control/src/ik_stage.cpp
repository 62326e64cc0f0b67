#include "avar/control/ik_stage.hpp"

#include <algorithm>
#include <stdexcept>

#include "avar/kinematics/ik_options.hpp"
#include "avar/kinematics/ik_solver.hpp"

namespace avar::control {

IkStage::IkStage(const RigKinematics& kinematics, const playback::Show& show, std::span<const double> rest_frame)
    : kinematics_(kinematics),
      show_(show),
      workspace_(kinematics.model, std::max<std::size_t>(1, show.targets.size())),
      cursors_(3 * show.targets.size()),
      q_(kinematics.model.dof(), 0.0),
      q_next_(kinematics.model.dof(), 0.0) {
  const kinematics::Model& model = kinematics.model;
  std::vector<char> moved(kinematics.bindings.size(), 0);
  for (const playback::TargetTrack& target : show.targets) {
    const auto effector = model.find_effector(target.effector);
    if (!effector) throw std::invalid_argument("the rig's kinematics has no effector '" + target.effector + "'");
    kinematics::IkGoal goal;
    goal.effector = *effector;
    goal.kind = target.kind == playback::TargetKind::aim ? kinematics::IkGoalKind::aim : kinematics::IkGoalKind::position;
    goal.aim_axis = Eigen::Vector3d(target.aim_axis[0], target.aim_axis[1], target.aim_axis[2]);
    goals_.push_back(goal);
    for (std::size_t b : bindings_moving(kinematics, *effector)) moved[b] = 1;
  }
  for (std::size_t b = 0; b < kinematics.bindings.size(); ++b)
    if (moved[b]) {
      driven_bindings_.push_back(b);
      driven_channels_.push_back(kinematics.bindings[b].channel);
    }
  reseed(rest_frame);
}

void IkStage::reseed(std::span<const double> frame) noexcept {
  const kinematics::Model& model = kinematics_.model;
  for (const JointBinding& b : kinematics_.bindings)
    q_[b.q_index] = std::clamp(b.to_joint(frame[b.channel]), model.lower_limits()[b.q_index], model.upper_limits()[b.q_index]);
  cold_ = true;
}

kinematics::IkResult IkStage::apply(double t, std::span<double> frame) noexcept {
  if (goals_.empty()) return {kinematics::IkStatus::converged, 0, 0, 0};
  const double local = show_.local_time(t);
  for (std::size_t i = 0; i < goals_.size(); ++i) {
    const playback::TargetTrack& target = show_.targets[i];
    for (int axis = 0; axis < 3; ++axis)
      goals_[i].position[axis] = target.xyz[static_cast<std::size_t>(axis)].evaluate(local, cursors_[3 * i + static_cast<std::size_t>(axis)]);
  }
  const kinematics::IkOptions options = cold_ ? kinematics::cold_start_ik_options() : kinematics::default_ik_options();
  const kinematics::IkResult result = kinematics::solve_ik(kinematics_.model, workspace_, goals_, q_, q_next_, options);
  switch (result.status) {
    case kinematics::IkStatus::converged: ++stats_.converged; break;
    case kinematics::IkStatus::degraded: ++stats_.degraded; break;
    case kinematics::IkStatus::failed: ++stats_.failed; break;
  }
  if (result.status != kinematics::IkStatus::failed) {
    std::copy(q_next_.begin(), q_next_.end(), q_.begin());
    cold_ = false;
    stats_.worst_position_error = std::max(stats_.worst_position_error, result.position_error);
    stats_.worst_orientation_error = std::max(stats_.worst_orientation_error, result.orientation_error);
  }
  for (std::size_t b : driven_bindings_) {
    const JointBinding& binding = kinematics_.bindings[b];
    frame[binding.channel] = binding.to_channel(q_[binding.q_index]);
  }
  return result;
}

}  // namespace avar::control
