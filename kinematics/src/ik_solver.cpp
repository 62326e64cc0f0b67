#include "avar/kinematics/ik_solver.hpp"

#include <cassert>
#include <cmath>

#include "ik_evaluation.hpp"

namespace avar::kinematics {
namespace {

bool finite_positive(double w) noexcept { return std::isfinite(w) && w > 0; }

bool goal_is_valid(const Model& model, const IkGoal& goal) noexcept {
  if (goal.effector >= model.effector_count()) return false;
  if (!goal.position.allFinite() || !goal.orientation.coeffs().allFinite() || !goal.aim_axis.allFinite()) return false;
  switch (goal.kind) {
    case IkGoalKind::position: return finite_positive(goal.position_weight);
    case IkGoalKind::orientation: return finite_positive(goal.orientation_weight) && goal.orientation.norm() > 1e-12;
    case IkGoalKind::pose:
      return finite_positive(goal.position_weight) && finite_positive(goal.orientation_weight) &&
             goal.orientation.norm() > 1e-12;
    case IkGoalKind::aim: return finite_positive(goal.orientation_weight) && goal.aim_axis.norm() > 1e-12;
  }
  return false;
}

detail::Attempt run(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, const IkOptions& options) noexcept {
  switch (options.method) {
    case IkMethod::damped_least_squares: return detail::run_damped_least_squares(model, ik, goals, options);
    case IkMethod::pseudo_inverse: return detail::run_pseudo_inverse(model, ik, goals, options);
    case IkMethod::jacobian_transpose: return detail::run_jacobian_transpose(model, ik, goals, options);
    case IkMethod::cyclic_coordinate_descent: return detail::run_cyclic_coordinate_descent(model, ik, goals, options);
  }
  return {};
}

void random_configuration(const Model& model, IkWorkspace& ik) noexcept {
  for (Eigen::Index k = 0; k < ik.q.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double unit = static_cast<double>(ik.rng() >> 11) * 0x1.0p-53;
    ik.q[k] = model.lower_limits()[i] + unit * (model.upper_limits()[i] - model.lower_limits()[i]);
  }
}

void write(const Eigen::VectorXd& q, std::span<double> out) noexcept {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = q[static_cast<Eigen::Index>(i)];
}

}  // namespace

IkResult solve_ik(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, std::span<const double> seed,
                  std::span<double> out, const IkOptions& options) noexcept {
  assert(seed.size() == model.dof() && out.size() == model.dof());
  assert(ik.dof() == model.dof() && ik.fk.joint_count() == model.joint_count());
  assert(options.preferred.empty() || options.preferred.size() == model.dof());

  bool valid = !goals.empty() && goals.size() <= ik.max_goals();
  for (const IkGoal& goal : goals) valid = valid && goal_is_valid(model, goal);
  for (std::size_t i = 0; i < seed.size(); ++i) {
    const bool finite = std::isfinite(seed[i]);
    valid = valid && finite;
    ik.q[static_cast<Eigen::Index>(i)] = finite ? seed[i] : 0;
  }
  detail::clamp_to_limits(model, ik.q);
  if (!valid) {
    write(ik.q, out);
    return {IkStatus::failed, 0, 0, 0};
  }

  detail::Attempt best = run(model, ik, goals, options);
  int iterations = best.iterations;
  ik.q_best = ik.q;
  for (int restart = 0; restart < options.restarts && !best.converged; ++restart) {
    random_configuration(model, ik);
    const detail::Attempt attempt = run(model, ik, goals, options);
    iterations += attempt.iterations;
    if (attempt.converged || attempt.cost < best.cost) {
      best = attempt;
      ik.q_best = ik.q;
    }
  }
  if (!best.converged && !best.stationary) {
    ik.q = ik.q_best;
    best.stationary = detail::nearly_stationary(model, ik, goals);
  }
  write(ik.q_best, out);
  const IkStatus status = best.converged ? IkStatus::converged : best.stationary ? IkStatus::degraded : IkStatus::failed;
  return {status, iterations, best.errors.position, best.errors.orientation};
}

}  // namespace avar::kinematics
