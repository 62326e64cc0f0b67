// Jacobian transpose (Parent, Computer Animation, App. B.4): dq = alpha J^T e, alpha chosen by
// Buss to minimise |e - alpha J J^T e| in the linearisation: alpha = |J^T e|^2 / |J J^T e|^2.

#include "ik_evaluation.hpp"

namespace avar::kinematics::detail {

Attempt run_jacobian_transpose(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                               const IkOptions& options) noexcept {
  const Eigen::Index rows = stacked_rows(goals);
  Attempt at;
  at.cost = evaluate(model, ik, goals, ik.q, at.errors);
  at.iterations = 1;
  while (!(at.converged = within_tolerance(at.errors, options)) && at.iterations < options.max_iterations) {
    fill_jacobian(model, ik, goals);
    const auto J = ik.J.topRows(rows);
    ik.g.noalias() = J.transpose() * ik.e.head(rows);
    drop_blocked(model, ik.q, ik.g);
    ik.A.noalias() = J.transpose() * J;
    ik.dq.noalias() = ik.A * ik.g;
    const double along = ik.g.dot(ik.dq);
    if (!(along > 0)) {
      at.stationary = true;
      break;
    }
    ik.dq = (ik.g.squaredNorm() / along) * ik.g;
    if (!descend_along(model, ik, goals, options, at)) break;
  }
  return at;
}

}  // namespace avar::kinematics::detail
