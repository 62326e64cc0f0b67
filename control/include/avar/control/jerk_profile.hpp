#pragma once
// Time-optimal jerk-limited motion of one axis to rest at a goal.
//
// From a state (p, v, a) the profile reaches (goal, 0, 0) with piecewise-constant jerk in
// {-J, 0, +J}, |a| <= A and |v| <= V throughout (when the start has |a| <= A and can keep
// |v| <= V, i.e. |v + a|a|/(2J)| <= V, which holds for every state on such a profile). It has
// three parts: a time-optimal velocity change from (v, a) to a peak velocity vp with a = 0, a
// cruise at vp (only when |vp| = V), and a time-optimal velocity change from (vp, 0) to rest.
// The distance D(vp) of the two changes is closed-form; vp solves D(vp) = goal - p, or vp = ±V
// and the cruise fills the rest. D is increasing beyond both 0 and the natural velocity
// v + a|a|/(2J); the root is bracketed on that branch (or between them) and found by Newton
// steps from the previous plan's peak, safeguarded by regula falsi and bisection, in the variable
// sqrt(|vp - natural|) where D has a square-root corner. A step is taken unevaluated where its
// residual is predicted within what the plan may miss by: from the Newton steps' convergence,
// or on the first step of a long plan by Taylor (D'' and D''' are closed-form too), where that
// step is of second order. When the peak jumps (a goal that stops
// or turns back), models from the branch ends start the solve next to the root: a move from
// rest after releasing the acceleration, the corner's slope in sqrt(|vp - natural|), or
// braking to rest plus the stop's vp sqrt(|vp|/J). The plan is then shifted by the solve's
// last bits so that it ends exactly on the goal. A state on a plan re-plans to the same plan, so
// re-planning every tick toward a held goal follows one optimal profile. Units: any length unit,
// seconds. plan() and at() are real-time safe (no allocation, exception or lock) and bounded
// (typically 1-6 evaluations of D, at most kMaxEvaluations).

#include <array>
#include <cstddef>

namespace avar::control {

struct MotionState {
  double p = 0;  ///< position, units
  double v = 0;  ///< velocity, units/s
  double a = 0;  ///< acceleration, units/s²
};

struct JerkLimits {
  double velocity = 1;      ///< V, units/s, > 0
  double acceleration = 1;  ///< A, units/s², > 0
  double jerk = 1;          ///< J, units/s³, > 0
};

/// Where braking at the limits (the time-optimal change to v = 0, a = 0) brings `s` to rest.
double stopping_point(const MotionState& s, const JerkLimits& limits) noexcept;

/// The peak velocity of the time-optimal move of `distance` from rest to rest (closed form): the
/// exact first guess for a plan from rest. Each half of the move is a velocity change of vp that
/// takes vp/A + A/J when it reaches A (vp >= A²/J), else 2 sqrt(vp/J), and covers vp times half
/// of that; the peak is V when the distance allows.
double rest_to_rest_peak(double distance, const JerkLimits& limits) noexcept;

/// How far from its goal a plan that lasts long may end. Such a plan is only followed for a
/// tick before the next one replaces it from where it got to, so its end need not be exact; the
/// plans that end soon are always solved to rounding.
struct PlanSlack {
  double distance = 0;  ///< units, >= 0; keep it below the goal's distance to any position limit
  double after = 0;     ///< s: plans that end sooner than this are solved to rounding
};

/// How the distance D of a plan's velocity change and stop grows with its peak velocity vp, at
/// vp: D' (s) and D'' (s²/units); NaN where not known.
struct PeakSensitivity {
  double slope = 0;
  double curvature = 0;
  bool before_fall = false;  ///< the state is still before its velocity change's fall
};

/// The peak of the plan toward a goal moved by `goal_step` (units) from the state `d` was taken
/// at, from the peak `d` was taken at: the root of D's second-order expansion there (where it
/// has one; else a Newton step). Exact to third order in goal_step where d is exact.
double moved_goal_peak(const PeakSensitivity& d, double peak, double goal_step) noexcept;

class JerkProfile {
 public:
  /// Plans from `from` to rest at `goal`. `from.a` is taken within [-A, A]. `hint`: a peak
  /// velocity to try first (the previous plan's peak_velocity() makes a re-plan toward the same
  /// goal cost one evaluation); any finite value is safe.
  /// `slack`: see PlanSlack (none by default: every plan ends on the goal to rounding).
  void plan(const MotionState& from, double goal, const JerkLimits& limits, double hint = 0, PlanSlack slack = {}) noexcept;

  /// The state `t` seconds after the start of the plan; at or after duration(): exactly
  /// (goal, 0, 0).
  MotionState at(double t) const noexcept;

  /// Seconds from the start to rest at the goal.
  double duration() const noexcept { return duration_; }
  /// The velocity between the two changes (the cruise velocity when |vp| = V), units/s.
  double peak_velocity() const noexcept { return peak_; }
  /// D' and D'' at this plan's peak for the plan from its state `t` seconds on to the same peak.
  /// While that state is in the first velocity change, that plan is the rest of this one, so its
  /// residual at this peak is exactly how far the goal has moved since: with these, a Newton (or
  /// second-order) step from this peak is the next plan's first guess. NaN past the change and
  /// for plans that cruise (their cruise, not their peak, takes up a goal's move).
  PeakSensitivity peak_sensitivity(double t) const noexcept;
  /// True when the plan ends on its goal to rounding, not only within its slack: following it
  /// to the end is then the motion that re-planning it every tick toward the same goal makes.
  bool ends_on_goal() const noexcept { return !loose_; }
  /// True when the velocity change speeds up toward the peak: its first jerk has the peak's sign.
  bool speeds_up() const noexcept { return pieces_[0].jerk * peak_ > 0; }
  /// How many times the last plan() evaluated the distance D (its cost): 1 for a re-plan from a
  /// state on the previous plan toward the same goal, never more than kMaxEvaluations.
  int evaluations() const noexcept { return evaluations_; }
  /// Every loop of plan() has a fixed bound: at most 6 Newton steps from the hint (taken twice
  /// when a predicted last step is not confirmed by the plan's end), 3 evaluations to bracket the
  /// root, 64 safeguarded refinements (which also stop as soon as vp stops changing in its last
  /// bit). Should the refinements reach their bound, the plan takes the
  /// bracket's end that falls short of the goal and finishes with a short cruise at its velocity
  /// (exact and within the limits, barely slower than optimal).
  static constexpr int kMaxEvaluations = 2 * 6 + 3 + 64;

 private:
  /// The state t seconds along the pieces, before the shift onto the goal.
  MotionState follow(double t) const noexcept;
  /// One solve and build; with `predict`, Newton may stop on a step predicted to converge, and
  /// false is returned when the plan's end does not certify it (the caller solves again without).
  /// `slack`: a residual this small is accepted (recorded in loose_ when it exceeds rounding).
  bool plan_once(const MotionState& from, double goal, const JerkLimits& limits, double hint, bool predict,
                 const PlanSlack& slack) noexcept;

  struct Piece {
    double duration = 0;  ///< s
    double jerk = 0;      ///< units/s³
  };
  static constexpr std::size_t kPieces = 7;  ///< 3 (change) + 1 (cruise) + 3 (stop)

  MotionState start_;
  double goal_ = 0;
  double peak_ = 0;
  JerkLimits limits_;
  double inverse_acceleration_ = 0, inverse_jerk_ = 0;  ///< 1/A, 1/J of the last plan
  double stop_peak_ = 0;  ///< |peak acceleration| of the last plan's stop
  double duration_ = 0;
  int evaluations_ = 0;
  bool loose_ = false;  ///< the plan ends within its slack of the goal, not to rounding
  double offset_ = 0;  ///< added to every position so that the plan ends exactly on the goal
  std::array<Piece, kPieces> pieces_{};
};

}  // namespace avar::control
