// Pseudo-inverse through the SVD with a secondary task in the null space (Parent, Computer
// Animation, App. B.4): dq = J+ e + (I - J+ J) gain (preferred - q), where J+ keeps the singular
// values above a floor, so I - J+ J = I - V_r V_r^T with V_r the kept right singular vectors.

#include <cmath>

#include "ik_evaluation.hpp"

namespace avar::kinematics::detail {
namespace {

constexpr double kRelativeSingularFloor = 1e-6;

}  // namespace

Attempt run_pseudo_inverse(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                           const IkOptions& options) noexcept {
  const Eigen::Index rows = stacked_rows(goals);
  const Eigen::Index dof = ik.q.size();
  // The SVD runs on the full preallocated matrix (a fixed size never reallocates); rows beyond
  // this solve's goals must be zero so that they add nothing.
  ik.J.bottomRows(ik.J.rows() - rows).setZero();
  ik.e.tail(ik.e.size() - rows).setZero();
  const bool secondary = options.preferred.size() == static_cast<std::size_t>(dof) && options.null_space_gain > 0;
  Attempt at;
  at.cost = evaluate(model, ik, goals, ik.q, at.errors);
  at.iterations = 1;
  while (!(at.converged = within_tolerance(at.errors, options)) && at.iterations < options.max_iterations) {
    fill_jacobian(model, ik, goals);
    ik.svd.compute(ik.J);
    const auto& s = ik.svd.singularValues();
    const Eigen::Index k = s.size();
    const double floor = kRelativeSingularFloor * std::max(s[0], 1e-300);
    auto coordinates = ik.g.head(k);
    coordinates.noalias() = ik.svd.matrixU().transpose() * ik.e;
    Eigen::Index kept = 0;
    for (Eigen::Index i = 0; i < k; ++i) {
      if (s[i] > floor) {
        coordinates[i] /= s[i];
        ++kept;
      } else {
        coordinates[i] = 0;
      }
    }
    ik.dq.noalias() = ik.svd.matrixV() * coordinates;
    if (secondary) {
      for (Eigen::Index j = 0; j < dof; ++j)
        ik.q_trial[j] = options.null_space_gain * (options.preferred[static_cast<std::size_t>(j)] - ik.q[j]);
      const auto V = ik.svd.matrixV().leftCols(kept);
      auto projected = ik.g.head(kept);
      projected.noalias() = V.transpose() * ik.q_trial;
      ik.q_trial.noalias() -= V * projected;
      ik.dq += ik.q_trial;
    }
    if (!descend_along(model, ik, goals, options, at)) break;
  }
  return at;
}

}  // namespace avar::kinematics::detail
