// Cyclic coordinate descent (Parent, Computer Animation, ch. 5): joints one at a time, from the
// last to the first, each set to the value that minimises the weighted error with all others held.
// For a revolute joint (world axis a through point p) every goal term has the form
// -w (R(theta) u) . v: u = effector - p, v = target - p for a position; u, v = matching columns of
// the current and target rotations for an orientation (weight halved, since the trace gives
// 1 + 2 cos angle); u = aim axis, v = line of sight for an aim. The best theta is then
// atan2(sum w a.(u x v), sum w (u.v - (a.u)(a.v))). A prismatic joint moves the positions only:
// s = sum w a.(target - effector) / sum w.

#include <algorithm>
#include <cmath>

#include "avar/kinematics/forward_kinematics.hpp"
#include "ik_evaluation.hpp"

namespace avar::kinematics::detail {
namespace {

struct Pull {
  double sine = 0;
  double cosine = 0;
  void add(const Eigen::Vector3d& a, const Eigen::Vector3d& u, const Eigen::Vector3d& v, double w) noexcept {
    sine += w * a.dot(u.cross(v));
    cosine += w * (u.dot(v) - a.dot(u) * a.dot(v));
  }
};

/// The change of joint `i` that minimises the weighted error, at the configuration in ik.fk.
double best_move(const Model& model, const IkWorkspace& ik, std::span<const IkGoal> goals, std::size_t i) noexcept {
  const Joint& joint = model.joint(i);
  const Eigen::Isometry3d& frame = ik.fk.joint_pose(i);
  const Eigen::Vector3d a = frame.linear() * joint.axis;
  const Eigen::Vector3d p = frame.translation();
  Pull pull;
  double slide = 0, slide_weight = 0;
  for (const IkGoal& goal : goals) {
    if (!ik.moves[i * model.effector_count() + goal.effector]) continue;
    const Eigen::Isometry3d pose = effector_pose(model, ik.fk, goal.effector);
    const double wp = goal.position_weight * goal.position_weight;
    const double wo = goal.orientation_weight * goal.orientation_weight;
    if (wants_position(goal)) {
      pull.add(a, pose.translation() - p, goal.position - p, wp);
      slide += wp * a.dot(goal.position - pose.translation());
      slide_weight += wp;
    }
    if (goal.kind == IkGoalKind::aim) {
      const Eigen::Vector3d sight = goal.position - pose.translation();
      if (sight.norm() > 1e-12) pull.add(a, pose.linear() * goal.aim_axis.normalized(), sight.normalized(), wo);
    } else if (wants_rotation(goal)) {
      const Eigen::Matrix3d target = goal.orientation.normalized().toRotationMatrix();
      for (int c = 0; c < 3; ++c) pull.add(a, pose.linear().col(c), target.col(c), 0.5 * wo);
    }
  }
  if (joint.type == JointType::prismatic) return slide_weight > 0 ? slide / slide_weight : 0;
  if (pull.sine == 0 && pull.cosine == 0) return 0;
  return std::atan2(pull.sine, pull.cosine);
}

}  // namespace

Attempt run_cyclic_coordinate_descent(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals,
                                      const IkOptions& options) noexcept {
  Attempt at;
  at.cost = evaluate(model, ik, goals, ik.q, at.errors);
  at.iterations = 1;
  while (!(at.converged = within_tolerance(at.errors, options)) && at.iterations < options.max_iterations) {
    const double sweep_start = at.cost;
    for (std::size_t i = model.joint_count(); i-- > 0 && at.iterations < options.max_iterations;) {
      const Joint& joint = model.joint(i);
      if (!joint.movable()) continue;
      const double move = best_move(model, ik, goals, i);
      if (move == 0) continue;
      const auto k = static_cast<Eigen::Index>(joint.q_index);
      const double previous = ik.q[k];
      ik.q[k] = std::clamp(previous + move, model.lower_limits()[joint.q_index], model.upper_limits()[joint.q_index]);
      GoalErrors errors;
      const double cost = evaluate(model, ik, goals, ik.q, errors);
      ++at.iterations;
      if (cost <= at.cost) {
        at.cost = cost;
        at.errors = errors;
        if ((at.converged = within_tolerance(at.errors, options))) return at;
      } else {
        // Clamping (or a mixed goal) made this move worse: undo it.
        ik.q[k] = previous;
        evaluate(model, ik, goals, ik.q, at.errors);
        ++at.iterations;
      }
    }
    if (sweep_start - at.cost <= kStalledDecrease * sweep_start) {
      at.stationary = true;
      break;
    }
  }
  return at;
}

}  // namespace avar::kinematics::detail
