#pragma once
// What an inverse-kinematics solve should achieve: one goal per effector, several goals on one
// tree solved together. All targets are in the world frame (the Model's base frame); lengths in
// metres, angles in radians. Plain values: cheap to rebuild every tick, real-time safe.

#include <Eigen/Geometry>

#include <cstddef>

namespace avar::kinematics {

enum class IkGoalKind {
  position,     ///< the effector origin at `position`
  orientation,  ///< the effector frame turned to `orientation`
  pose,         ///< both, the two errors weighted by position_weight and orientation_weight
  aim,          ///< the effector-frame axis `aim_axis`, from the effector origin, points at `position`
};

struct IkGoal {
  std::size_t effector = 0;  ///< index into Model::effectors()
  IkGoalKind kind = IkGoalKind::pose;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< world, m: the target point (position, pose, aim)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< effector frame -> world (orientation, pose)
  Eigen::Vector3d aim_axis = Eigen::Vector3d::UnitX();  ///< effector frame, any non-zero length (aim)
  /// Relative weights of the position error (per metre) and the orientation or aim error (per
  /// radian) in the least-squares objective; both must be > 0 where they are used. They trade
  /// one goal against another when not all can be met; they do not change the tolerances.
  double position_weight = 1;
  double orientation_weight = 1;

  static IkGoal at_position(std::size_t effector, const Eigen::Vector3d& target, double weight = 1) noexcept {
    IkGoal g;
    g.effector = effector;
    g.kind = IkGoalKind::position;
    g.position = target;
    g.position_weight = weight;
    return g;
  }
  static IkGoal at_orientation(std::size_t effector, const Eigen::Quaterniond& target, double weight = 1) noexcept {
    IkGoal g;
    g.effector = effector;
    g.kind = IkGoalKind::orientation;
    g.orientation = target;
    g.orientation_weight = weight;
    return g;
  }
  static IkGoal at_pose(std::size_t effector, const Eigen::Isometry3d& target, double position_weight = 1,
                        double orientation_weight = 1) noexcept {
    IkGoal g;
    g.effector = effector;
    g.kind = IkGoalKind::pose;
    g.position = target.translation();
    g.orientation = Eigen::Quaterniond(target.linear());
    g.position_weight = position_weight;
    g.orientation_weight = orientation_weight;
    return g;
  }
  static IkGoal aiming(std::size_t effector, const Eigen::Vector3d& axis, const Eigen::Vector3d& target,
                       double weight = 1) noexcept {
    IkGoal g;
    g.effector = effector;
    g.kind = IkGoalKind::aim;
    g.aim_axis = axis;
    g.position = target;
    g.orientation_weight = weight;
    return g;
  }
};

/// Rows the goal adds to the stacked error: 3 for position, orientation and aim, 6 for pose.
constexpr std::size_t ik_goal_rows(IkGoalKind kind) noexcept { return kind == IkGoalKind::pose ? 6 : 3; }

}  // namespace avar::kinematics
