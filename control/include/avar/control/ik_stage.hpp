#pragma once
// The inverse-kinematics stage of a tick: the show's target tracks, sampled at show time, become
// goals for the rig's kinematic model; the solver, warm-started from the previous tick's answer,
// finds joint values within the joint limits (the channels' limits); those are written as the
// targets of the channels that drive the joints on the goals' paths. Channels of joints no goal
// moves keep what their tracks say. A failed solve keeps the previous joint values; a degraded
// one (target out of reach) uses the closest pose the solver found.
//
// Construction allocates (load time); apply() is real-time safe: no allocation, exception, lock
// or logging. One thread.

#include <cstdint>
#include <span>
#include <vector>

#include "avar/control/live_layer.hpp"
#include "avar/control/target_aims.hpp"
#include "avar/rig/rig.hpp"
#include "avar/kinematics/ik_goal.hpp"
#include "avar/kinematics/ik_result.hpp"
#include "avar/kinematics/ik_workspace.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::control {

/// Counts of solve outcomes since construction, and the worst residuals seen.
struct IkStats {
  std::uint64_t converged = 0;
  std::uint64_t degraded = 0;
  std::uint64_t failed = 0;
  double worst_position_error = 0;     ///< m
  double worst_orientation_error = 0;  ///< rad (aim angle)
};

/// Counts a solve's outcome, and its residuals when it is usable (not failed); returns whether it
/// is. Real-time safe.
bool record_ik_outcome(IkStats& stats, const kinematics::IkResult& result) noexcept;

class IkStage {
 public:
  /// kinematics and show are borrowed and must outlive the stage. rest_frame: the rig's rest
  /// pose (channel units), the first seed. Throws std::invalid_argument for a target whose
  /// effector the model does not have (config::check_show_against_rig reports it first).
  IkStage(const rig::RigKinematics& kinematics, const playback::Show& show, std::span<const double> rest_frame);

  /// Solves for the targets at playing time t (seconds; wrapped like the tracks) and writes the
  /// driven channels' targets into frame (indexed by channel). The show's goal points first go
  /// through `live` (LiveLayer::apply_targets at loop time now_s: live controls steering a
  /// target); then a target `aims` holds is solved for its held point instead. Real-time safe
  /// when live's apply_targets is.
  kinematics::IkResult apply(double t, std::span<double> frame, const TargetAims* aims = nullptr, LiveLayer* live = nullptr,
                             double now_s = 0) noexcept;

  /// Where target `index` was last asked to be (metres, the rig's base frame): the show's point,
  /// or the held one. Before the first apply(): the origin.
  const Eigen::Vector3d& goal_position(std::size_t index) const noexcept { return goals_[index].position; }
  std::size_t goal_count() const noexcept { return goals_.size(); }

  /// Seeds the next solve from a frame of channel values (the pose the figure is in), and makes
  /// it a cold start (random restarts allowed). Real-time safe.
  void reseed(std::span<const double> frame) noexcept;

  const IkStats& stats() const noexcept { return stats_; }
  /// Channels this stage writes.
  std::span<const std::size_t> driven_channels() const noexcept { return driven_channels_; }

 private:
  void mix_live(LiveLayer& live, double now_s) noexcept;

  const rig::RigKinematics& kinematics_;
  const playback::Show& show_;
  kinematics::IkWorkspace workspace_;
  std::vector<kinematics::IkGoal> goals_;
  std::vector<playback::CurveCursor> cursors_;  ///< 6 per target: x, y, z, roll, pitch, yaw
  std::vector<double> q_, q_next_;
  std::vector<double> effector_points_;       ///< 3 per effector of the model: what `live` mixes
  std::vector<std::size_t> driven_bindings_;  ///< indices into kinematics_.bindings
  std::vector<std::size_t> driven_channels_;
  bool cold_ = true;
  IkStats stats_;
};

}  // namespace avar::control
