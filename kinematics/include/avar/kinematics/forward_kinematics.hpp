#pragma once
// Forward kinematics of a joint tree (Parent, Computer Animation, ch. 5: each joint's frame is
// its parent's frame composed with the joint's fixed origin and its motion). Real-time safe:
// no allocation, no exception, no lock; one Workspace per thread, the Model shared read-only.

#include <Eigen/Geometry>

#include <cstddef>
#include <span>

#include "avar/core/status.hpp"
#include "avar/kinematics/model.hpp"
#include "avar/kinematics/workspace.hpp"

namespace avar::kinematics {

/// Computes the world pose of every joint frame into `ws` for the joint vector q (entry
/// joint.q_index per movable joint: rad for revolute, m for prismatic joints; limits are not
/// applied). Joint i's frame is parent frame * origin * motion(q), the motion being a rotation
/// about, or a translation along, the joint's axis; joints on the base take the world frame as
/// parent. Returns Status::not_finite, leaving `ws` untouched, when q holds a NaN or infinity.
/// Preconditions (asserted): q.size() == model.dof(), `ws` was made for `model`.
Status forward_kinematics(const Model& model, std::span<const double> q, Workspace& ws) noexcept;

/// World pose of an effector (effector frame -> world) from the last forward_kinematics().
/// Precondition (asserted): effector < model.effector_count(), `ws` was made for `model`.
Eigen::Isometry3d effector_pose(const Model& model, const Workspace& ws, std::size_t effector) noexcept;

}  // namespace avar::kinematics
