#pragma once
// Per-loop scratch for one Model (the "data" half of the model/data split): the world pose of
// every joint frame. Constructing it is the only allocation; forward_kinematics and
// geometric_jacobian then run on it without allocating. One Workspace per thread.

#include <Eigen/Geometry>

#include <cstddef>
#include <span>
#include <vector>

#include "avar/core/status.hpp"
#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

class Workspace {
 public:
  /// Sized for `model` (load time: allocates). Poses start at the identity.
  explicit Workspace(const Model& model);

  std::size_t joint_count() const noexcept { return joint_poses_.size(); }
  /// World pose of a joint's frame (joint frame -> world) from the last forward_kinematics().
  /// Real-time safe.
  const Eigen::Isometry3d& joint_pose(std::size_t joint) const noexcept { return joint_poses_[joint]; }

 private:
  friend Status forward_kinematics(const Model& model, std::span<const double> q, Workspace& ws) noexcept;

  std::vector<Eigen::Isometry3d> joint_poses_;
};

}  // namespace avar::kinematics
