#pragma once
// Serial chains of revolute joints from Denavit-Hartenberg parameters, in either convention.
// Load time only: allocates and throws InputError. Lengths in metres, angles in radians.

#include <Eigen/Geometry>

#include <span>

#include "avar/core/input_error.hpp"
#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

/// One DH row: the link parameters of one revolute joint and its limits.
struct DhRow {
  double a = 0;
  double alpha = 0;
  double d = 0;
  double theta = 0;  ///< offset added to the joint variable
  double lower = 0;  ///< joint limits, rad
  double upper = 0;
  SourceLocation where;  ///< where the row was read, for errors; may be empty
};

/// Standard (distal) DH, row i holding (a_i, alpha_i, d_i, theta_i):
///   T_i(q_i) = RotZ(q_i + theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i),
/// base -> DH frame n = T_1 ... T_n. The model's joints are "joint1".."jointN" (q in row order);
/// joint i's frame is DH frame i-1 turned by q_i (its z axis is the joint axis). One effector,
/// "tip", at DH frame n followed by `tool`.
/// Throws InputError at a row's `where` for non-finite parameters or limits with lower > upper,
/// and for no rows at all.
Model chain_from_standard_dh(std::span<const DhRow> rows, const Eigen::Isometry3d& tool = Eigen::Isometry3d::Identity());

/// Modified (proximal, Craig) DH, row i holding (a_{i-1}, alpha_{i-1}, d_i, theta_i):
///   T_i(q_i) = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i + q_i) TransZ(d_i),
/// base -> DH frame n = T_1 ... T_n. Joints "joint1".."jointN"; joint i's frame is DH frame i.
/// One effector, "tip", at DH frame n followed by `tool`. Errors as for chain_from_standard_dh.
Model chain_from_modified_dh(std::span<const DhRow> rows, const Eigen::Isometry3d& tool = Eigen::Isometry3d::Identity());

}  // namespace avar::kinematics
