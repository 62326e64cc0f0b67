#include "ik_evaluation.hpp"

#include <limits>

#include <algorithm>
#include <cmath>

#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/jacobian.hpp"

namespace avar::kinematics::detail {
namespace {

/// The rotation vector (axis * angle, angle in [0, pi]) of a unit quaternion.
Eigen::Vector3d rotation_vector(Eigen::Quaterniond r) noexcept {
  if (r.w() < 0) r.coeffs() = -r.coeffs();
  const double s = r.vec().norm();
  if (s < 1e-12) return 2 * r.vec();
  return r.vec() * (2 * std::atan2(s, r.w()) / s);
}

/// The rotation vector that turns unit vector `from` onto unit vector `to` about their common normal.
Eigen::Vector3d alignment_vector(const Eigen::Vector3d& from, const Eigen::Vector3d& to) noexcept {
  const Eigen::Vector3d normal = from.cross(to);
  const double s = normal.norm();
  const double c = from.dot(to);
  if (s > 1e-12) return normal * (std::atan2(s, c) / s);
  if (c > 0) return Eigen::Vector3d::Zero();
  // Opposite: any axis perpendicular to `from` will do.
  const Eigen::Vector3d other = std::abs(from.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return from.cross(other).normalized() * M_PI;
}

double largest(const Eigen::Vector3d& v) noexcept { return v.cwiseAbs().maxCoeff(); }

}  // namespace

Eigen::Index stacked_rows(std::span<const IkGoal> goals) noexcept {
  Eigen::Index rows = 0;
  for (const IkGoal& goal : goals) rows += static_cast<Eigen::Index>(ik_goal_rows(goal.kind));
  return rows;
}

double evaluate(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, const Eigen::VectorXd& q,
                GoalErrors& errors) noexcept {
  // A non-finite configuration has no pose: it costs infinitely, so no solver accepts it.
  if (forward_kinematics(model, std::span<const double>(q.data(), static_cast<std::size_t>(q.size())), ik.fk) != Status::ok) {
    errors = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    return std::numeric_limits<double>::infinity();
  }
  errors = {};
  Eigen::Index row = 0;
  for (const IkGoal& goal : goals) {
    const Eigen::Isometry3d pose = effector_pose(model, ik.fk, goal.effector);
    if (wants_position(goal)) {
      const Eigen::Vector3d error = goal.position - pose.translation();
      errors.position = std::max(errors.position, largest(error));
      ik.e.segment<3>(row) = goal.position_weight * error;
      row += 3;
    }
    if (wants_rotation(goal)) {
      Eigen::Vector3d error;
      if (goal.kind == IkGoalKind::aim) {
        const Eigen::Vector3d axis = pose.linear() * goal.aim_axis.normalized();
        const Eigen::Vector3d sight = goal.position - pose.translation();
        const double distance = sight.norm();
        error = distance > 1e-12 ? alignment_vector(axis, sight / distance) : Eigen::Vector3d::Zero();
        errors.orientation = std::max(errors.orientation, error.norm());
      } else {
        error = rotation_vector(goal.orientation.normalized() * Eigen::Quaterniond(pose.linear()).conjugate());
        errors.orientation = std::max(errors.orientation, largest(error));
      }
      ik.e.segment<3>(row) = goal.orientation_weight * error;
      row += 3;
    }
  }
  return 0.5 * ik.e.head(row).squaredNorm();
}

void fill_jacobian(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals) noexcept {
  Eigen::Index row = 0;
  for (const IkGoal& goal : goals) {
    geometric_jacobian(model, ik.fk, goal.effector, ik.J_effector);
    if (wants_position(goal)) {
      ik.J.middleRows(row, 3) = goal.position_weight * ik.J_effector.topRows<3>();
      row += 3;
    }
    if (wants_rotation(goal)) {
      ik.J.middleRows(row, 3) = goal.orientation_weight * ik.J_effector.bottomRows<3>();
      row += 3;
    }
  }
}

bool within_tolerance(const GoalErrors& errors, const IkOptions& options) noexcept {
  return errors.position <= options.position_tolerance && errors.orientation <= options.orientation_tolerance;
}

bool descend_along(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, const IkOptions& options,
                   Attempt& at) noexcept {
  constexpr int kHalvings = 8;
  GoalErrors trial_errors;
  for (int halving = 0; halving <= kHalvings && at.iterations < options.max_iterations; ++halving) {
    ik.q_trial = ik.q + ik.dq;
    clamp_to_limits(model, ik.q_trial);
    const double trial_cost = evaluate(model, ik, goals, ik.q_trial, trial_errors);
    ++at.iterations;
    if (trial_cost < at.cost) {
      ik.q = ik.q_trial;
      at.cost = trial_cost;
      at.errors = trial_errors;
      return true;
    }
    ik.dq *= 0.5;
  }
  evaluate(model, ik, goals, ik.q, at.errors);
  at.converged = within_tolerance(at.errors, options);
  at.stationary = !at.converged && at.iterations < options.max_iterations;
  return false;
}

bool nearly_stationary(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals) noexcept {
  constexpr double kRelativeGradient = 1e-3;
  const Eigen::Index rows = stacked_rows(goals);
  GoalErrors errors;
  evaluate(model, ik, goals, ik.q, errors);
  fill_jacobian(model, ik, goals);
  const auto J = ik.J.topRows(rows);
  ik.g.noalias() = J.transpose().lazyProduct(ik.e.head(rows));
  drop_blocked(model, ik.q, ik.g);
  return ik.g.norm() <= kRelativeGradient * J.norm() * ik.e.head(rows).norm();
}

void clamp_to_limits(const Model& model, Eigen::VectorXd& q) noexcept {
  const auto lower = model.lower_limits();
  const auto upper = model.upper_limits();
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    q[k] = std::clamp(q[k], lower[i], upper[i]);
  }
}

void drop_blocked(const Model& model, const Eigen::VectorXd& q, Eigen::VectorXd& d) noexcept {
  const auto lower = model.lower_limits();
  const auto upper = model.upper_limits();
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    if ((q[k] <= lower[i] && d[k] < 0) || (q[k] >= upper[i] && d[k] > 0)) d[k] = 0;
  }
}

}  // namespace avar::kinematics::detail
