#include "avar/control/ik_stage.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "avar/kinematics/ik_options.hpp"
#include "avar/kinematics/ik_solver.hpp"

namespace avar::control {

bool record_ik_outcome(IkStats& stats, const kinematics::IkResult& result) noexcept {
  switch (result.status) {
    case kinematics::IkStatus::converged: ++stats.converged; break;
    case kinematics::IkStatus::degraded: ++stats.degraded; break;
    case kinematics::IkStatus::failed: ++stats.failed; return false;
  }
  stats.worst_position_error = std::max(stats.worst_position_error, result.position_error);
  stats.worst_orientation_error = std::max(stats.worst_orientation_error, result.orientation_error);
  return true;
}

IkStage::IkStage(const rig::RigKinematics& kinematics, const playback::Show& show, std::span<const double> rest_frame)
    : kinematics_(kinematics),
      show_(show),
      workspace_(kinematics.model, std::max<std::size_t>(1, show.targets.size())),
      cursors_(6 * show.targets.size()),
      q_(kinematics.model.dof(), 0.0),
      q_next_(kinematics.model.dof(), 0.0),
      effector_points_(3 * kinematics.model.effector_count(), 0.0) {
  const kinematics::Model& model = kinematics.model;
  std::vector<char> moved(kinematics.bindings.size(), 0);
  for (const playback::TargetTrack& target : show.targets) {
    const auto effector = model.find_effector(target.effector);
    if (!effector) throw std::invalid_argument("the rig's kinematics has no effector '" + target.effector + "'");
    kinematics::IkGoal goal;
    goal.effector = *effector;
    switch (target.kind) {
      case playback::TargetKind::position: goal.kind = kinematics::IkGoalKind::position; break;
      case playback::TargetKind::aim: goal.kind = kinematics::IkGoalKind::aim; break;
      case playback::TargetKind::orientation: goal.kind = kinematics::IkGoalKind::orientation; break;
      case playback::TargetKind::pose: goal.kind = kinematics::IkGoalKind::pose; break;
    }
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
  for (const rig::JointBinding& b : kinematics_.bindings)
    q_[b.q_index] = std::clamp(b.to_joint(frame[b.channel]), model.lower_limits()[b.q_index], model.upper_limits()[b.q_index]);
  cold_ = true;
}

void IkStage::mix_live(LiveLayer& live, double now_s) noexcept {
  std::fill(effector_points_.begin(), effector_points_.end(), std::numeric_limits<double>::quiet_NaN());
  for (const kinematics::IkGoal& goal : goals_)
    for (Eigen::Index a = 0; a < 3; ++a) effector_points_[3 * goal.effector + static_cast<std::size_t>(a)] = goal.position[a];
  live.apply_targets(now_s, effector_points_);
  for (kinematics::IkGoal& goal : goals_) {
    const Eigen::Vector3d mixed(effector_points_[3 * goal.effector], effector_points_[3 * goal.effector + 1],
                                effector_points_[3 * goal.effector + 2]);
    if (mixed.allFinite()) goal.position = mixed;
  }
}

kinematics::IkResult IkStage::apply(double t, std::span<double> frame, const TargetAims* aims, LiveLayer* live,
                                    double now_s) noexcept {
  if (goals_.empty()) return {kinematics::IkStatus::converged, 0, 0, 0};
  const double local = show_.local_time(t);
  double rpy[3] = {0, 0, 0};
  for (std::size_t i = 0; i < goals_.size(); ++i) {
    const playback::TargetTrack& target = show_.targets[i];
    // A path gives the point, and the orientation when it orients; orientation keys give the
    // orientation; what remains comes from the x, y, z and roll, pitch, yaw curves.
    const bool path_orients = target.path && target.path->orients();
    const bool point_curves = target.has_point() && !target.path;
    const bool angle_curves = target.has_orientation() && !target.orientation_keys && !path_orients;
    if (target.path) {
      const playback::PathSample sample = target.path->sample(local);
      goals_[i].position = sample.position;
      if (path_orients) goals_[i].orientation = sample.orientation;
    }
    if (target.orientation_keys) goals_[i].orientation = target.orientation_keys->evaluate(local);
    for (std::size_t a = 0; a < 3; ++a) {
      if (point_curves) goals_[i].position[static_cast<Eigen::Index>(a)] = target.xyz[a].evaluate(local, cursors_[6 * i + a]);
      if (angle_curves) rpy[a] = target.rpy[a].evaluate(local, cursors_[6 * i + 3 + a]);
    }
    if (angle_curves)
      goals_[i].orientation = Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX());
  }
  if (live) mix_live(*live, now_s);
  // A target held by hand: its point, the show's orientation, above any live control.
  if (aims)
    for (std::size_t i = 0; i < goals_.size(); ++i)
      if (aims->held(i)) goals_[i].position = aims->point(i);
  const kinematics::IkOptions options = cold_ ? kinematics::cold_start_ik_options() : kinematics::default_ik_options();
  const kinematics::IkResult result = kinematics::solve_ik(kinematics_.model, workspace_, goals_, q_, q_next_, options);
  if (record_ik_outcome(stats_, result)) {
    std::copy(q_next_.begin(), q_next_.end(), q_.begin());
    cold_ = false;
  }
  for (std::size_t b : driven_bindings_) {
    const rig::JointBinding& binding = kinematics_.bindings[b];
    frame[binding.channel] = binding.to_channel(q_[binding.q_index]);
  }
  return result;
}

}  // namespace avar::control
