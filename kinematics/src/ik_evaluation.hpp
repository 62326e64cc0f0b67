#pragma once
// Internal to the IK solvers: the stacked weighted error of a set of goals and its Jacobian,
// and the pieces every solver shares (limits, tolerance test). Real-time safe.

#include <span>

#include "avar/kinematics/ik_goal.hpp"
#include "avar/kinematics/ik_options.hpp"
#include "avar/kinematics/ik_workspace.hpp"
#include "avar/kinematics/model.hpp"

namespace avar::kinematics::detail {

/// Unweighted errors at one configuration: the largest |component| over all goals.
struct GoalErrors {
  double position = 0;     ///< m
  double orientation = 0;  ///< rad (aim: the angle between the axis and the line of sight)
};

/// The relative decrease of the error that counts as no progress (a solver stops as stationary).
inline constexpr double kStalledDecrease = 1e-14;

/// One solver run from ik.q: where it ended (ik.q holds the best configuration seen).
struct Attempt {
  double cost = 0;  ///< 0.5 |e|^2 of the weighted error at ik.q
  GoalErrors errors;
  int iterations = 0;
  bool converged = false;
  bool stationary = false;  ///< stopped because no step lowers the error (a local minimum)
};

inline bool wants_position(const IkGoal& goal) noexcept {
  return goal.kind == IkGoalKind::position || goal.kind == IkGoalKind::pose;
}
inline bool wants_rotation(const IkGoal& goal) noexcept { return goal.kind != IkGoalKind::position; }

/// Rows of the stacked error for these goals.
Eigen::Index stacked_rows(std::span<const IkGoal> goals) noexcept;

/// Runs forward kinematics at q into ik.fk and writes the weighted error (target minus current:
/// position, rotation vector, aim rotation vector) into the top rows of ik.e. Returns 0.5 |e|^2.
double evaluate(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, const Eigen::VectorXd& q,
                GoalErrors& errors) noexcept;

/// Writes the weighted rows of the geometric Jacobian matching ik.e into the top rows of ik.J,
/// at the configuration of the last evaluate().
void fill_jacobian(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals) noexcept;

bool within_tolerance(const GoalErrors& errors, const IkOptions& options) noexcept;

/// Projects q onto the box of joint limits.
void clamp_to_limits(const Model& model, Eigen::VectorXd& q) noexcept;

/// Zeroes the components of a descent direction d that would push a joint at a limit past it.
void drop_blocked(const Model& model, const Eigen::VectorXd& q, Eigen::VectorXd& d) noexcept;

/// Line search along ik.dq from ik.q: tries q + dq (projected onto the limits), halving dq up to
/// 8 times, until the error falls; then moves ik.q there, updates `at` and returns true. When no
/// trial lowers it, restores ik.fk and ik.e at ik.q, sets at.converged / at.stationary and
/// returns false. Every trial counts as an iteration.
bool descend_along(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, const IkOptions& options,
                   Attempt& at) noexcept;

/// Whether ik.q is, to first order, a local minimum of the weighted error within the limits: the
/// gradient J^T e (less the parts that push joints on a limit past it) is tiny against |J| |e|.
/// For runs that end on their iteration budget while still creeping toward such a point (the
/// closest reachable pose to an unreachable target is usually singular, where progress is slow).
bool nearly_stationary(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals) noexcept;

// The numeric methods: each runs from ik.q (within limits) and leaves its best configuration there.
Attempt run_damped_least_squares(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                                 const IkOptions& options) noexcept;
Attempt run_pseudo_inverse(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                           const IkOptions& options) noexcept;
Attempt run_jacobian_transpose(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                               const IkOptions& options) noexcept;
Attempt run_cyclic_coordinate_descent(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                                      const IkOptions& options) noexcept;

}  // namespace avar::kinematics::detail
