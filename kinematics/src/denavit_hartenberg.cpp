#include "avar/kinematics/denavit_hartenberg.hpp"

#include <cmath>
#include <string>

#include "avar/core/format.hpp"
#include "avar/kinematics/model_builder.hpp"

namespace avar::kinematics {
namespace {

Eigen::Isometry3d rot_z(double angle) { return Eigen::Isometry3d(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())); }
Eigen::Isometry3d rot_x(double angle) { return Eigen::Isometry3d(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())); }
Eigen::Isometry3d trans_z(double d) { return Eigen::Isometry3d(Eigen::Translation3d(0, 0, d)); }
Eigen::Isometry3d trans_x(double a) { return Eigen::Isometry3d(Eigen::Translation3d(a, 0, 0)); }

std::string joint_name(std::size_t i) { return "joint" + std::to_string(i + 1); }

/// Row i's link parameters; the standard convention places them in the next joint's origin, so
/// they are checked here, where the error can name their own row.
void require_finite_parameters(std::size_t i, const DhRow& row) {
  if (!std::isfinite(row.a) || !std::isfinite(row.alpha) || !std::isfinite(row.d) || !std::isfinite(row.theta))
    throw InputError(row.where, "joint '" + joint_name(i) + "': expected finite DH parameters, found a " + format_number(row.a) +
                                    ", alpha " + format_number(row.alpha) + ", d " + format_number(row.d) + ", theta " +
                                    format_number(row.theta));
}

JointSpec revolute(std::size_t i, const Eigen::Isometry3d& origin, const DhRow& row) {
  require_finite_parameters(i, row);
  return {joint_name(i), JointType::revolute, i == 0 ? std::string() : joint_name(i - 1), origin,
          Eigen::Vector3d::UnitZ(), row.lower, row.upper};
}

void require_rows(std::span<const DhRow> rows) {
  if (rows.empty()) throw InputError({}, "expected at least one DH row, found none");
}

}  // namespace

Model chain_from_standard_dh(std::span<const DhRow> rows, const Eigen::Isometry3d& tool) {
  require_rows(rows);
  // The joint turns first, about z of DH frame i-1; the rest of row i is fixed and becomes the
  // origin of joint i+1 (or, after the last row, part of the tip's tool transform).
  ModelBuilder builder;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DhRow& row = rows[i];
    builder.add_joint(revolute(i, origin, row), row.where);
    origin = rot_z(row.theta) * trans_z(row.d) * trans_x(row.a) * rot_x(row.alpha);
  }
  builder.add_effector({"tip", joint_name(rows.size() - 1), origin * tool});
  return builder.build();
}

Model chain_from_modified_dh(std::span<const DhRow> rows, const Eigen::Isometry3d& tool) {
  require_rows(rows);
  // RotZ(theta + q) TransZ(d) = RotZ(theta) TransZ(d) RotZ(q): everything in row i but the joint
  // rotation is joint i's fixed origin, and the joint frame is DH frame i itself.
  ModelBuilder builder;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DhRow& row = rows[i];
    builder.add_joint(revolute(i, rot_x(row.alpha) * trans_x(row.a) * rot_z(row.theta) * trans_z(row.d), row), row.where);
  }
  builder.add_effector({"tip", joint_name(rows.size() - 1), tool});
  return builder.build();
}

}  // namespace avar::kinematics
