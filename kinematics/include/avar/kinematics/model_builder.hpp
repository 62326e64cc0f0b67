#pragma once
// Builds a Model joint by joint, validating each joint and effector as it is added, so an error
// points at the first bad declaration. Load time only: allocates and throws InputError.

#include <Eigen/Geometry>

#include <cstddef>
#include <string>
#include <unordered_map>

#include "avar/core/input_error.hpp"
#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

struct JointSpec {
  std::string name;
  JointType type = JointType::revolute;
  std::string parent;  ///< name of an earlier joint; empty: attached to the base
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< parent frame -> joint frame at q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           ///< any length > 0; ignored when fixed
  double lower = 0;  ///< rad or m; ignored when fixed
  double upper = 0;
};

struct EffectorSpec {
  std::string name;
  std::string joint;  ///< name of the joint it is attached to
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< joint frame -> effector frame
};

class ModelBuilder {
 public:
  /// Adds a joint after every joint added so far and returns its index in the Model. Movable
  /// joints take the next entry of q, in the order they are added. The axis is normalised.
  /// Throws InputError at `where` (which may be empty) for: an empty or duplicate name, a parent
  /// that is not an earlier joint (joints come parents first, so no cycle can form), an origin
  /// that is not a finite rigid transform, a zero or non-finite axis, non-finite limits or
  /// lower > upper.
  std::size_t add_joint(const JointSpec& spec, const SourceLocation& where = {});

  /// Adds a named effector. Throws InputError at `where` for: an empty or duplicate effector
  /// name, an unknown joint, a tool that is not a finite rigid transform.
  std::size_t add_effector(const EffectorSpec& spec, const SourceLocation& where = {});

  /// The model of everything added so far (which is valid by construction).
  Model build() const { return model_; }

 private:
  Model model_;
  std::unordered_map<std::string, std::size_t> joint_index_;
  std::unordered_map<std::string, std::size_t> effector_index_;
};

}  // namespace avar::kinematics
