#pragma once
// An immutable kinematic model: a tree of joints (revolute, prismatic, fixed) in topological
// order (every parent before its children), each placed relative to its parent's frame, and
// named end effectors. Only ModelBuilder makes one, after validating it; per-loop scratch lives
// in a separate Workspace (the model/data split of pinocchio), so a Model is shared read-only
// by any number of threads. Lengths in metres, angles in radians.

#include <Eigen/Geometry>

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::kinematics {

enum class JointType { revolute, prismatic, fixed };

struct Joint {
  static constexpr std::size_t kNoParent = std::numeric_limits<std::size_t>::max();
  static constexpr std::size_t kNoVariable = std::numeric_limits<std::size_t>::max();

  std::string name;
  JointType type = JointType::revolute;
  std::size_t parent = kNoParent;  ///< index of the parent joint; kNoParent: attached to the base
  /// Parent joint frame -> this joint's frame at q = 0 (the base frame for a joint on the base).
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  /// Unit axis in this joint's frame: rotation axis (right hand) or direction of travel.
  /// Zero for fixed joints.
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  double lower = 0;  ///< limits, rad or m; 0 for fixed joints
  double upper = 0;
  std::size_t q_index = kNoVariable;  ///< position in the joint vector q; kNoVariable when fixed
  SourceLocation where;               ///< where the joint was declared, when it came from a file

  bool on_base() const noexcept { return parent == kNoParent; }
  bool movable() const noexcept { return q_index != kNoVariable; }
};

/// A frame rigidly attached to a joint's frame (a hand, an eye's line of sight).
struct Effector {
  std::string name;
  std::size_t joint = 0;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< joint frame -> effector frame
  SourceLocation where;
};

class Model {
 public:
  std::span<const Joint> joints() const noexcept { return joints_; }
  const Joint& joint(std::size_t index) const noexcept { return joints_[index]; }
  std::size_t joint_count() const noexcept { return joints_.size(); }

  std::span<const Effector> effectors() const noexcept { return effectors_; }
  const Effector& effector(std::size_t index) const noexcept { return effectors_[index]; }
  std::size_t effector_count() const noexcept { return effectors_.size(); }

  /// Number of movable joints: the length of the joint vector q.
  std::size_t dof() const noexcept { return lower_.size(); }
  /// Limits per entry of q (rad for revolute, m for prismatic joints).
  std::span<const double> lower_limits() const noexcept { return lower_; }
  std::span<const double> upper_limits() const noexcept { return upper_; }

  /// Name lookups for load time (linear search; resolve names to indices once).
  std::optional<std::size_t> find_joint(std::string_view name) const;
  std::optional<std::size_t> find_effector(std::string_view name) const;

 private:
  friend class ModelBuilder;
  Model() = default;

  std::vector<Joint> joints_;
  std::vector<Effector> effectors_;
  std::vector<double> lower_;
  std::vector<double> upper_;
};

}  // namespace avar::kinematics
