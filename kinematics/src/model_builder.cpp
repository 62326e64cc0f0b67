#include "avar/kinematics/model_builder.hpp"

#include <cmath>
#include <optional>

#include "avar/core/format.hpp"

namespace avar::kinematics {
namespace {

bool known(const SourceLocation& where) { return !where.file.empty() || where.line > 0; }

std::string declared_at(const SourceLocation& where) {
  return known(where) ? " (declared at " + to_string(where) + ")" : std::string();
}

/// What is wrong with a transform that should be rigid, if anything.
std::optional<std::string> rigid_problem(const Eigen::Isometry3d& t, const std::string& what) {
  if (!t.linear().allFinite() || !t.translation().allFinite())
    return what + " has non-finite entries; expected a finite rigid transform";
  const Eigen::Matrix3d r = t.linear();
  if (!(r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || std::abs(r.determinant() - 1) > 1e-9)
    return what + " is not rigid; expected a rotation (orthonormal columns, determinant +1) and a translation";
  return std::nullopt;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return "(" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) + ")";
}

}  // namespace

std::size_t ModelBuilder::add_joint(const JointSpec& spec, const SourceLocation& where) {
  if (spec.name.empty()) throw InputError(where, "expected a joint name, found an empty one");
  const auto fail = [&](const std::string& problem) { throw InputError(where, "joint '" + spec.name + "': " + problem); };

  if (const auto taken = joint_index_.find(spec.name); taken != joint_index_.end())
    fail("the name is taken by joint " + std::to_string(taken->second) + declared_at(model_.joints_[taken->second].where) +
         "; expected unique joint names");
  Joint joint;
  joint.name = spec.name;
  joint.type = spec.type;
  joint.where = where;
  if (!spec.parent.empty()) {
    const auto parent = joint_index_.find(spec.parent);
    if (parent == joint_index_.end())
      fail("parent '" + spec.parent +
           "' is not a joint declared before it; expected the name of an earlier joint (parents come before "
           "their children) or no parent for a joint on the base");
    joint.parent = parent->second;
  }
  if (const auto problem = rigid_problem(spec.origin, "the origin")) fail(*problem);
  joint.origin = spec.origin;

  if (spec.type != JointType::fixed) {
    const double length = spec.axis.norm();
    if (!std::isfinite(length) || length < 1e-12)
      fail("expected a non-zero finite axis, found " + vector_text(spec.axis));
    if (!std::isfinite(spec.lower) || !std::isfinite(spec.upper) || spec.lower > spec.upper)
      fail("expected finite limits with lower <= upper, found lower " + format_number(spec.lower) + ", upper " +
           format_number(spec.upper));
    joint.axis = spec.axis / length;
    joint.lower = spec.lower;
    joint.upper = spec.upper;
    joint.q_index = model_.lower_.size();
    model_.lower_.push_back(spec.lower);
    model_.upper_.push_back(spec.upper);
  }
  const std::size_t index = model_.joints_.size();
  model_.joints_.push_back(std::move(joint));
  joint_index_.emplace(spec.name, index);
  return index;
}

std::size_t ModelBuilder::add_effector(const EffectorSpec& spec, const SourceLocation& where) {
  if (spec.name.empty()) throw InputError(where, "expected an effector name, found an empty one");
  const auto fail = [&](const std::string& problem) { throw InputError(where, "effector '" + spec.name + "': " + problem); };

  if (const auto taken = effector_index_.find(spec.name); taken != effector_index_.end())
    fail("the name is taken by effector " + std::to_string(taken->second) +
         declared_at(model_.effectors_[taken->second].where) + "; expected unique effector names");
  const auto joint = joint_index_.find(spec.joint);
  if (joint == joint_index_.end())
    fail("joint '" + spec.joint + "' does not exist; expected the name of a joint added before the effector");
  if (const auto problem = rigid_problem(spec.tool, "the tool transform")) fail(*problem);

  const std::size_t index = model_.effectors_.size();
  model_.effectors_.push_back({spec.name, joint->second, spec.tool, where});
  effector_index_.emplace(spec.name, index);
  return index;
}

}  // namespace avar::kinematics
