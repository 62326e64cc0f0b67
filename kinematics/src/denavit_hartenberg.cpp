#include "avar/kinematics/denavit_hartenberg.hpp"

#include <fstream>
#include <sstream>

namespace avar::kinematics {
namespace {

Eigen::Isometry3d rot_z(double a) { return Eigen::Isometry3d(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ())); }
Eigen::Isometry3d rot_x(double a) { return Eigen::Isometry3d(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX())); }
Eigen::Isometry3d move(double x, double y, double z) { return Eigen::Isometry3d(Eigen::Translation3d(x, y, z)); }

Joint revolute(std::size_t i, int parent, const Eigen::Isometry3d& origin, const DhRow& r) {
  Joint j;
  j.name = "joint" + std::to_string(i + 1);
  j.type = JointType::revolute;
  j.parent = parent;
  j.origin = origin;
  j.axis = Eigen::Vector3d::UnitZ();
  j.lower = r.lower;
  j.upper = r.upper;
  return j;
}

}  // namespace

Model chain_from_standard_dh(std::span<const DhRow> rows) {
  // The joint rotates first (about z of the previous DH frame); the rest of row i is a fixed
  // offset that becomes the origin of joint i+1, and the last one the tip's tool transform.
  ModelBuilder builder;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DhRow& r = rows[i];
    builder.add_joint(revolute(i, static_cast<int>(i) - 1, origin, r));
    origin = rot_z(r.theta) * move(0, 0, r.d) * move(r.a, 0, 0) * rot_x(r.alpha);
  }
  if (!rows.empty()) builder.add_effector({"tip", rows.size() - 1, origin});
  return builder.build();
}

Model chain_from_modified_dh(std::span<const DhRow> rows) {
  // RotZ(theta + q) TransZ(d) = RotZ(theta) TransZ(d) RotZ(q): the whole row but the joint
  // rotation is the joint's fixed origin.
  ModelBuilder builder;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DhRow& r = rows[i];
    builder.add_joint(revolute(i, static_cast<int>(i) - 1, rot_x(r.alpha) * move(r.a, 0, 0) * rot_z(r.theta) * move(0, 0, r.d), r));
  }
  if (!rows.empty()) builder.add_effector({"tip", rows.size() - 1, Eigen::Isometry3d::Identity()});
  return builder.build();
}

std::vector<NamedDhChain> read_dh_chains(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, "cannot read file");
  std::vector<NamedDhChain> chains;
  std::size_t expected_rows = 0;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string first;
    if (!(words >> first)) continue;
    if (first == "chain") {
      if (expected_rows != 0)
        throw InputError({path, number, 1}, "chain '" + chains.back().name + "' still expects " + std::to_string(expected_rows) + " rows");
      NamedDhChain chain;
      long long dof = 0;
      if (!(words >> chain.name >> dof) || dof <= 0)
        throw InputError({path, number, 1}, "expected 'chain <name> <dof>' with dof > 0");
      expected_rows = static_cast<std::size_t>(dof);
      chains.push_back(std::move(chain));
      continue;
    }
    if (expected_rows == 0) throw InputError({path, number, 1}, "expected 'chain <name> <dof>' before DH rows");
    std::istringstream row(line);
    DhRow r;
    std::string extra;
    if (!(row >> r.a >> r.alpha >> r.d >> r.theta >> r.lower >> r.upper) || (row >> extra))
      throw InputError({path, number, 1}, "expected six numbers: a alpha d theta lower upper");
    chains.back().rows.push_back(r);
    --expected_rows;
  }
  if (expected_rows != 0) throw InputError({path, 0, 0}, "chain '" + chains.back().name + "' ends early");
  return chains;
}

}  // namespace avar::kinematics
