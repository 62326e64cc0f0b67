#pragma once
// The solve's first stage: Newton steps from a hint (the last plan's peak), kept on its branch.

#include <algorithm>
#include <cmath>
#include <limits>

#include "jerk_branches.hpp"
#include "jerk_residuals.hpp"
#include "jerk_taylor.hpp"

namespace avar::control::jerk {

/// Bound of the warm-started Newton steps from the hint.
inline constexpr int kMaxWarmSteps = 6;

/// What the warm start learnt, for the bracketed solve should it not converge: on a branch
/// where D increases (beyond both 0 and the natural velocity), evaluated points below and above
/// the root bracket it; the last Newton iterate is the best start.
struct WarmStart {
  double below = std::numeric_limits<double>::quiet_NaN(), f_below = 0;
  double above = std::numeric_limits<double>::quiet_NaN(), f_above = 0;
  double resume;
  /// Where the last Newton step (in vp) pointed when that was past both 0 and the natural
  /// velocity from a branch beyond them (the goal turned back; NaN otherwise): the bracketed
  /// solve then evaluates first the branch end on that side.
  double pointed = std::numeric_limits<double>::quiet_NaN();
  bool brackets() const { return below == below && above == above; }
};

/// A re-plan toward the same goal from a state on the last plan has the same peak: try it
/// first, with a few Newton steps kept on its branch (so that a target that moves a little
/// each tick costs a few evaluations). Ends the solve in `out` when a step is accepted, reaches
/// ±V short of the goal (the cruise fills the rest) or, with `predict`, is predicted to converge.
/// A hint that is not finite is not tried.
[[gnu::always_inline]] inline WarmStart warm_start(double hint, bool predict, const PlanSlack& slack, double V, const Branches& b,
                                                   const Bounds& bounds, Residuals& residual, Solution& out) {
  WarmStart w;
  w.resume = hint;
  if (!std::isfinite(hint)) return w;
  const double natural = b.natural, low = b.low, high = b.high;
  double previous_residual = 0;
  const double lo = hint >= high ? high : hint <= low ? -V : low;
  const double hi = hint >= high ? V : hint <= low ? low : high;
  // On a branch that starts at the natural velocity, D grows like sqrt(|vp - natural|) there
  // (a state on the stopping part of a plan has its root right at that corner): Newton runs in
  // u = sqrt(|vp - natural|), where D is smooth, as in the bracketed refinement; at the corner
  // itself (u = 0) with corner_slope.
  const CornerMap map{b.cornered(lo, hi), natural, lo == natural ? 1.0 : -1.0};
  // At the natural velocity itself on a smooth branch, take the branch's side of it (the
  // distance's slope there is that side's).
  double x = std::clamp(hint, lo, hi);
  if (x == natural && !map.mapped) x = std::nextafter(x, hint >= high ? V : -V);
  const double u_end = map.mapped ? std::sqrt(hi - lo) : 0.0;
  double u = map.mapped ? map.to_u(x) : 0.0;
  const bool monotone = lo >= high || hi <= low;
  const auto points_past_both = [&](double newton) { return (lo == high && newton < low) || (hi == low && newton > high); };
  for (int k = 0; k < kMaxWarmSteps; ++k) {
    const Reach r = residual(x);
    if (monotone && r.distance < 0 && !(x <= w.below)) w.below = x, w.f_below = r.distance;
    if (monotone && r.distance > 0 && !(x >= w.above)) w.above = x, w.f_above = r.distance;
    if (std::abs(x) == V && r.distance * x <= 0) {
      out.vp = x;
      out.cruise = -r.distance / x;
      break;
    }
    if (residual.accept(x, r, out)) break;
    double next = 0;
    if (map.mapped) {
      const double slope_u = u > 0 ? map.slope(r.slope, u) : b.corner_slope;
      const double u_next = std::clamp(u - r.distance / slope_u, 0.0, u_end);
      if (!(u_next > 0)) {
        // At the corner itself: the bracketed refinement takes over, told where a step in vp
        // points (when it points across the corner).
        const double newton = x - r.distance / r.slope;
        if (u > 0 && r.slope > 0 && points_past_both(newton)) w.pointed = newton;
        break;
      }
      // (At the branch's far end exactly that end, which the bracketed solve may evaluate.)
      next = u_next == u_end ? (map.dir > 0 ? hi : lo) : std::clamp(map.to_vp(u_next), lo, hi);
      u = u_next;
    } else {
      // A step that points past both 0 and the natural velocity: the root is likely on the
      // far side, whose end the bracketed solve then evaluates first. (A step that ends
      // between them is clamped to the near end, as any other: evaluating that end brackets a
      // root next to it.)
      const double newton = x - r.distance / r.slope;
      if (points_past_both(newton)) {
        w.pointed = newton;
        break;
      }
      next = std::clamp(newton, lo, hi);
    }
    if (!(next != x)) break;
    // Newton converges quadratically: r_next ~ K r² with K = r / r_previous² from the last
    // step. When that predicts a residual well within tolerance, take the step without
    // evaluating it; the plan's end certifies it (else the solve runs again in full).
    // On the first step (no previous residual yet) of a plan that outlasts the slack's
    // horizon, the Taylor estimate from D'' stands in for K where it applies
    // (newton_residual). (Plans that end sooner must end on the goal to rounding, which no
    // estimate predicts reliably: a miss would cost a second solve.)
    const bool outlasts = r.duration > slack.after;
    const double tolerance = residual.tolerance();
    double predicted_residual = std::numeric_limits<double>::quiet_NaN();
    if (predict && next > lo && next < hi && (k > 0 || outlasts)) {
      predicted_residual = k > 0 ? r.distance / (previous_residual * previous_residual) * r.distance * r.distance
                                 : newton_residual(r, x, next - x, bounds);
      const double allowed = outlasts ? std::max(tolerance, slack.distance) : tolerance;
      if (std::abs(predicted_residual) <= 0.25 * allowed) {
        out.vp = next;
        out.predicted = true;
        break;
      }
    }
    if (predict && k == 0 && outlasts && predicted_residual == predicted_residual) {
      // Where the Newton step's D'' step²/2 is known (the step stays inside r's regimes) but not
      // small enough on the first step, a second-order step leaves D''' step³/6. (Where it is
      // not known, the second-order step measured never inside either.)
      const SecondOrderStep second = second_order_step(r, x, bounds);
      const double to = x + second.step;
      if (to > lo && to < hi && std::abs(second.residual) <= 0.25 * std::max(tolerance, slack.distance)) {
        out.vp = to;
        out.predicted = true;
        break;
      }
    }
    previous_residual = r.distance;
    x = next;
    w.resume = next;
  }
  return w;
}

}  // namespace avar::control::jerk
