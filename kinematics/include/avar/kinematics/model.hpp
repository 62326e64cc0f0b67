#pragma once
// An immutable kinematic model: a tree of joints (revolute, prismatic, fixed) in topological
// order, each placed relative to its parent's frame, and named end effectors. Built and
// validated once by ModelBuilder; per-loop scratch lives in a separate Workspace (the model/data
// split), so FK and Jacobians never allocate. Lengths in metres, angles in radians.

#include <Eigen/Geometry>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::kinematics {

enum class JointType { revolute, prismatic, fixed };

struct Joint {
  std::string name;
  JointType type = JointType::revolute;
  int parent = -1;                                       ///< index of the parent joint; -1 = the base
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< parent frame -> this joint at q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();        ///< unit, in this joint's frame
  double lower = 0;                                      ///< limits (rad or m); fixed joints: 0
  double upper = 0;
  int q_index = -1;                                      ///< position in the joint vector; -1 when fixed
  SourceLocation where;
};

/// A frame of interest rigidly attached to a joint (a hand, an eye's line of sight).
struct Effector {
  std::string name;
  std::size_t joint = 0;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< joint frame -> effector frame
};

class Model {
 public:
  const std::vector<Joint>& joints() const noexcept { return joints_; }
  const std::vector<Effector>& effectors() const noexcept { return effectors_; }
  /// Number of movable joints: the length of the joint vector q.
  std::size_t dof() const noexcept { return dof_; }
  std::optional<std::size_t> find_joint(const std::string& name) const;
  std::optional<std::size_t> find_effector(const std::string& name) const;

 private:
  friend class ModelBuilder;
  std::vector<Joint> joints_;
  std::vector<Effector> effectors_;
  std::size_t dof_ = 0;
};

/// Collects joints and effectors and validates them into a Model. Throws InputError (at the
/// joint's `where` when given) for: a duplicate name, a parent that is not an earlier joint, a
/// zero or non-finite axis, non-finite origins, lower > upper, an effector on a missing joint.
class ModelBuilder {
 public:
  /// Adds a joint; its axis is normalised. Returns its index.
  std::size_t add_joint(Joint joint);
  void add_effector(Effector effector);
  Model build() const;

 private:
  std::vector<Joint> joints_;
  std::vector<Effector> effectors_;
};

}  // namespace avar::kinematics
