#pragma once
// Numeric inverse kinematics on a joint tree (Parent, Computer Animation, ch. 5 and App. B.4):
// joint values that bring the effectors to their goals, within the joint limits.
//
// Per tick, warm-started from the previous solution:
//   IkWorkspace ik(model, goal_count);                       // once, at load
//   const IkOptions options = default_ik_options();
//   ...
//   goals[0] = IkGoal::at_pose(hand, target);                // every tick
//   IkResult r = solve_ik(model, ik, goals, q_previous, q_next, options);
//   if (r.status != IkStatus::failed) q_previous = q_next;   // q_next is within limits either way
//
// Real-time safe: no allocation, no exception, no lock, no logging; bounded time (at most
// (1 + restarts) * max_iterations error evaluations). Thread safety: one IkWorkspace per thread.

#include <span>

#include "avar/kinematics/ik_goal.hpp"
#include "avar/kinematics/ik_options.hpp"
#include "avar/kinematics/ik_result.hpp"
#include "avar/kinematics/ik_workspace.hpp"
#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

/// Solves for `goals` from `seed` (entries of q: rad for revolute, m for prismatic joints; clamped
/// into the limits before the first step) and writes the answer to `out`, which is always within
/// the model's limits (every iterate is projected onto them) and finite. `seed` and `out` may
/// be the same span. Returns failed, with `out` = the clamped seed (zeros where the seed is not
/// finite), when: goals is empty or holds more than ik.max_goals(), an effector index is out
/// of range, a target, aim axis or weight is not finite, a weight is <= 0, an aim axis is zero,
/// or the seed is not finite.
/// Preconditions (asserted): seed.size() == out.size() == model.dof(), `ik` was made for `model`,
/// options.preferred is empty or of size dof.
IkResult solve_ik(const Model& model, IkWorkspace& ik, std::span<const IkGoal> goals, std::span<const double> seed,
                  std::span<double> out, const IkOptions& options = default_ik_options()) noexcept;

}  // namespace avar::kinematics
