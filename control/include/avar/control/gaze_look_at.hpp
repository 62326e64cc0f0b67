#pragma once
// Look-at gaze's eyes (playback::GazeLookAt): each eye effector of the rig's kinematic model is
// aimed at the gaze point with the solver the IkStage uses (kinematics::solve_ik, aim goals,
// damped least squares warm-started from the last answer). Only the eyes' own joints are solved
// (a model of them hung from the head's frame); the head, and every other joint, stays where the
// frame puts it, and the point is taken into the head's frame through forward kinematics of the
// whole figure, so the eyes counter-turn as the head moves and converge on a near point, each
// from its own centre.
//
// Construction allocates (load time); aim() is real-time safe: no allocation, exception, lock
// or logging. One thread.

#include <Eigen/Geometry>

#include <span>
#include <vector>

#include "avar/control/ik_stage.hpp"
#include "avar/kinematics/ik_goal.hpp"
#include "avar/kinematics/ik_workspace.hpp"
#include "avar/kinematics/model.hpp"
#include "avar/kinematics/workspace.hpp"
#include "avar/playback/runtime/gaze_aim.hpp"
#include "avar/playback/runtime/idle_spec.hpp"
#include "avar/rig/rig.hpp"

namespace avar::control {

class GazeLookAt final : public playback::GazeAim {
 public:
  /// `kinematics` is copied; `limits` (one per frame channel) gives the rest pose, the first seed,
  /// and the eye joints' range (inside the soft margins). Throws std::invalid_argument when the
  /// spec does not fit the model (config::load_idle_section reports it first, with its place).
  GazeLookAt(const rig::RigKinematics& kinematics, const playback::GazeLookAt& spec,
             std::span<const playback::IdleChannelLimits> limits);

  /// Writes the eye channels of `frame` (channel units) so that every eye looks at `point`, the
  /// rest of the figure posed as `frame` says. A failed solve keeps the last eye values; an
  /// unreachable point gives the closest sight lines the eyes' limits allow. Real-time safe.
  void aim(const playback::GazePoint& point, std::span<double> frame) noexcept override;

  /// The gaze point in the world (the model's base frame, m).
  Eigen::Vector3d world_point(const playback::GazePoint& point) const noexcept;
  /// Outcomes of the solves so far and their worst residuals (aim angle, rad).
  const IkStats& stats() const noexcept { return stats_; }

 private:
  kinematics::Model figure_;                     ///< the whole figure
  std::vector<rig::JointBinding> bindings_;      ///< the figure's, in its q order
  std::vector<rig::JointBinding> eye_bindings_;  ///< per entry of the eyes' q (filled with eyes_)
  kinematics::Model eyes_;                       ///< the eyes' own joints, on the head's frame
  std::size_t mount_;                            ///< figure joint the eyes hang from, or kOnBase
  Eigen::Vector3d centre_, ahead_, left_, up_;
  kinematics::Workspace figure_poses_;
  kinematics::IkWorkspace ik_;
  std::vector<kinematics::IkGoal> goals_;
  std::vector<double> figure_q_, q_, q_next_;
  bool cold_ = true;
  IkStats stats_;
};

}  // namespace avar::control
