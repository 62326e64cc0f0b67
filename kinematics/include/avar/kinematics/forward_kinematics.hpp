#pragma once
// Forward kinematics and the geometric Jacobian. All functions here are real-time safe once the
// Workspace exists: no allocation, no exception. One Workspace per thread.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <span>
#include <vector>

#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

/// Per-loop scratch sized once for a model: the world pose of every joint frame.
struct Workspace {
  explicit Workspace(const Model& model);
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> world;
};

/// World poses of every joint frame for joint vector q (size model.dof(); radians or metres).
/// Joint i's frame is parent frame * origin * motion(q), motion being a rotation about (or a
/// translation along) the joint's axis.
void forward_kinematics(const Model& model, std::span<const double> q, Workspace& ws) noexcept;

/// World pose of an effector after forward_kinematics().
Eigen::Isometry3d effector_pose(const Model& model, const Workspace& ws, std::size_t effector) noexcept;

/// Geometric Jacobian of an effector in the world frame after forward_kinematics(): rows 0-2
/// linear velocity of the effector origin, rows 3-5 angular velocity, one column per entry of
/// q; columns of joints not between the effector and the base are zero. J must be 6 x dof.
void geometric_jacobian(const Model& model, const Workspace& ws, std::size_t effector,
                        Eigen::Ref<Eigen::Matrix<double, 6, Eigen::Dynamic>> J) noexcept;

}  // namespace avar::kinematics
