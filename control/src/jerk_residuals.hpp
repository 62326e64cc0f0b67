#pragma once
// The solve's residual D(vp) - d, counted and remembered, and when it is small enough to end on.

#include <cfloat>
#include <cmath>
#include <limits>

#include "jerk_reach.hpp"

namespace avar::control::jerk {

/// Where the solve ended: the peak velocity (NaN until found) and the cruise at it.
struct Solution {
  double vp = std::numeric_limits<double>::quiet_NaN();
  double cruise = 0;       ///< s, at vp = ±V or to finish a bracket end that falls short
  bool predicted = false;  ///< vp was taken on a Newton step predicted to converge, unevaluated
  bool loose = false;      ///< the accepted residual is within the slack, not within rounding
  bool found() const { return vp == vp; }
};

/// D(vp) - d for the plan from (v0, a0) over d = goal - p, each evaluation counted in
/// `evaluations`. The solve comes back to branch ends and bracket ends it has evaluated, and ends
/// on one of them (whose change the plan keeps): the last two evaluations are remembered.
class Residuals {
 public:
  Residuals(const MotionState& start, double goal, const Bounds& k, const PlanSlack& slack, int& evaluations)
      : v0_(start.v),
        a0_(start.a),
        d_(goal - start.p),
        positions_(std::abs(start.p) + std::abs(goal)),
        k_(k),
        slack_(slack),
        evaluations_(evaluations),
        tolerance_(4 * DBL_EPSILON * positions_ + DBL_MIN) {}

  Reach operator()(double vp) {
    if (vp == last_vp_) return last_;
    if (vp == earlier_vp_) return earlier_;
    ++evaluations_;
    Reach r = reach(v0_, a0_, vp, k_);
    r.distance -= d_;
    tolerance_ = 4 * DBL_EPSILON * (positions_ + r.magnitude) + DBL_MIN;
    if (last_vp_ == last_vp_) earlier_vp_ = last_vp_, earlier_ = last_;  // (last is unset before the first)
    last_vp_ = vp;
    last_ = r;
    return r;
  }

  /// Reached to rounding: the last bits of the distance and of the last evaluation's terms are
  /// what the plan's end may miss by (and the plan is shifted by that onto the goal).
  double tolerance() const { return tolerance_; }
  /// A residual within rounding, or within the slack for a plan that lasts beyond its horizon.
  bool close_enough(const Reach& r) const {
    return std::abs(r.distance) <= tolerance_ || (std::abs(r.distance) <= slack_.distance && r.duration > slack_.after);
  }
  /// Ends the solve on x when its residual r is close enough.
  bool accept(double x, const Reach& r, Solution& out) const {
    if (!close_enough(r)) return false;
    out.vp = x;
    out.loose = std::abs(r.distance) > tolerance_;
    return true;
  }
  /// Whether vp is one of the last two evaluations, and that evaluation.
  bool remembers(double vp) const { return vp == last_vp_ || vp == earlier_vp_; }
  const Reach& remembered(double vp) const { return vp == last_vp_ ? last_ : earlier_; }

 private:
  double v0_, a0_, d_;
  double positions_;  ///< |p| + |goal|
  Bounds k_;
  PlanSlack slack_;
  int& evaluations_;
  double tolerance_;
  double last_vp_ = std::numeric_limits<double>::quiet_NaN(), earlier_vp_ = last_vp_;
  Reach last_, earlier_;
};

}  // namespace avar::control::jerk
