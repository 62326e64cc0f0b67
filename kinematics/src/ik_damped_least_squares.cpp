// Levenberg-Marquardt damped least squares with the error-adaptive damping of Sugihara
// ("Solvability-unconcerned inverse kinematics by the Levenberg-Marquardt method", 2011):
// lambda proportional to |e|^2 plus a floor, multiplied up after a step that does not lower the error and
// back down after one that does. Every trial configuration is projected onto the limits.

#include <algorithm>

#include "ik_evaluation.hpp"

namespace avar::kinematics::detail {
namespace {

// Tuned on the benchmark chains (bench/ik.cpp): lambda = boost (kErrorDamping |e|^2 + kDampingFloor).
constexpr double kErrorDamping = 0.1;
constexpr double kDampingFloor = 1e-9;
constexpr double kBoostDown = 0.1;
constexpr double kBoostUp = 10;
constexpr double kMaxBoost = 1e10;           ///< beyond this no step lowers the error: stationary

/// Joints sitting on a limit that the step would push past it are taken out of the system
/// (their row and column of A become the identity, their gradient zero) so that the remaining
/// joints make up for them instead of the step being cut by the projection. True if any was.
bool freeze_blocked(const Model& model, IkWorkspace& ik) noexcept {
  bool any = false;
  const auto lower = model.lower_limits();
  const auto upper = model.upper_limits();
  for (Eigen::Index k = 0; k < ik.q.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    if ((ik.q[k] <= lower[i] && ik.dq[k] < 0) || (ik.q[k] >= upper[i] && ik.dq[k] > 0)) {
      ik.A.row(k).setZero();
      ik.A.col(k).setZero();
      ik.A(k, k) = 1;
      ik.g[k] = 0;
      any = true;
    }
  }
  return any;
}

}  // namespace

Attempt run_damped_least_squares(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                                 const IkOptions& options) noexcept {
  const Eigen::Index rows = stacked_rows(goals);
  Attempt at;
  at.cost = evaluate(model, ik, goals, ik.q, at.errors);
  at.iterations = 1;
  fill_jacobian(model, ik, goals);
  double boost = 1;
  GoalErrors trial_errors;
  while (!(at.converged = within_tolerance(at.errors, options)) && at.iterations < options.max_iterations) {
    const auto J = ik.J.topRows(rows);
    // Coefficient-wise products: for a handful of rows and joints the blocked GEMM path costs more.
    ik.A.noalias() = J.transpose().lazyProduct(J);
    ik.g.noalias() = J.transpose().lazyProduct(ik.e.head(rows));
    ik.A.diagonal().array() += boost * (kErrorDamping * 2 * at.cost + kDampingFloor);
    ik.llt.compute(ik.A);
    ik.dq = ik.llt.solve(ik.g);
    if (freeze_blocked(model, ik)) {
      ik.llt.compute(ik.A);
      ik.dq = ik.llt.solve(ik.g);
    }
    ik.q_trial = ik.q + ik.dq;
    clamp_to_limits(model, ik.q_trial);
    ik.e_kept.head(rows) = ik.e.head(rows);
    const double trial_cost = evaluate(model, ik, goals, ik.q_trial, trial_errors);
    ++at.iterations;
    if (trial_cost < at.cost) {
      const bool stalled = at.cost - trial_cost <= kStalledDecrease * at.cost;
      ik.q = ik.q_trial;
      at.cost = trial_cost;
      at.errors = trial_errors;
      if (stalled) {
        at.converged = within_tolerance(at.errors, options);
        at.stationary = !at.converged;
        break;
      }
      fill_jacobian(model, ik, goals);
      boost = std::max(boost * kBoostDown, 1.0);
    } else {
      ik.e.head(rows) = ik.e_kept.head(rows);
      boost *= kBoostUp;
      if (boost > kMaxBoost) {
        at.stationary = true;
        break;
      }
    }
  }
  return at;
}

}  // namespace avar::kinematics::detail
