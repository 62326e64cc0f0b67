#pragma once
// Serial chains of revolute joints from Denavit-Hartenberg parameters, in either convention,
// as Models with one effector ("tip") at the last DH frame. Lengths in metres, angles in radians.

#include <span>
#include <string>
#include <vector>

#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

struct DhRow {
  double a = 0;
  double alpha = 0;
  double d = 0;
  double theta = 0;  ///< offset added to the joint variable
  double lower = 0;
  double upper = 0;
};

/// Standard (distal) DH: T_i = RotZ(q_i + theta) TransZ(d) TransX(a) RotX(alpha).
Model chain_from_standard_dh(std::span<const DhRow> rows);

/// Modified (proximal, Craig) DH, row i holding (a_{i-1}, alpha_{i-1}, d_i, theta_i):
/// T_i = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i + q_i) TransZ(d_i).
Model chain_from_modified_dh(std::span<const DhRow> rows);

struct NamedDhChain {
  std::string name;
  std::vector<DhRow> rows;
};

/// Reads chains in the text format of the IK benchmark reference file: `chain <name> <dof>`,
/// then <dof> rows `a alpha d theta lower upper` (standard DH); '#' starts a comment. Throws
/// InputError naming the file and line on any malformed entry.
std::vector<NamedDhChain> read_dh_chains(const std::string& path);

}  // namespace avar::kinematics
