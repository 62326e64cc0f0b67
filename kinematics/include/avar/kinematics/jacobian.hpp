#pragma once
// The geometric Jacobian of an effector (Parent, Computer Animation, ch. 5). Real-time safe: no
// allocation, no exception, no lock.

#include <Eigen/Core>

#include <cstddef>

#include "avar/kinematics/model.hpp"
#include "avar/kinematics/workspace.hpp"

namespace avar::kinematics {

/// Writes into J the geometric Jacobian of an effector at the configuration of the last
/// forward_kinematics() on `ws`, in the world frame: J * qdot = (v, w), v the linear velocity of
/// the effector origin (m/s), w the angular velocity of its frame (rad/s). Column k belongs to
/// entry k of q: a revolute joint with world axis z through world point p gives
/// (z x (effector - p), z), a prismatic joint (z, 0). Columns of joints that are not between the
/// effector and the base are zero.
/// Preconditions (asserted): J is 6 x model.dof(), effector < model.effector_count(), `ws` was
/// made for `model`.
void geometric_jacobian(const Model& model, const Workspace& ws, std::size_t effector,
                        Eigen::Ref<Eigen::Matrix<double, 6, Eigen::Dynamic>> J) noexcept;

}  // namespace avar::kinematics
