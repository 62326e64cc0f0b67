#include "avar/control/jerk_profile.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "jerk_bounds.hpp"
#include "jerk_reach.hpp"
#include "jerk_stop.hpp"
#include "jerk_taylor.hpp"
#include "jerk_velocity_change.hpp"

namespace avar::control {
namespace {

using jerk::Bounds;
using jerk::Reach;
using jerk::SecondOrderStep;
using jerk::VelocityChange;

/// A plan whose end misses the goal by at most this many rounding tolerances is shifted onto it.
constexpr double kShiftable = 64;
/// A plan taken on a predicted Newton step must end this close to the goal (in tolerances).
constexpr double kCertified = 4;
/// Bound of the bracketed refinement (each one evaluation of D).
constexpr int kMaxRefinements = 64;
/// Bound of the warm-started Newton steps from the hint.
constexpr int kMaxWarmSteps = 6;
static_assert(JerkProfile::kMaxEvaluations == 2 * kMaxWarmSteps + 3 + kMaxRefinements);

MotionState advance(MotionState s, double t, double jerk) {
  s.p += t * (s.v + t * (s.a / 2 + t * jerk / 6));
  s.v += t * (s.a + t * jerk / 2);
  s.a += t * jerk;
  return s;
}

}  // namespace

double stopping_point(const MotionState& s, const JerkLimits& limits) noexcept {
  const double a = std::clamp(s.a, -limits.acceleration, limits.acceleration);
  return s.p + jerk::velocity_change(s.v, a, 0, Bounds(limits)).distance;
}

double rest_to_rest_peak(double distance, const JerkLimits& limits) noexcept {
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  const double d = std::abs(distance);
  // The distance of the move with peak v: v (v/A + A/J) when A is reached, else 2 v sqrt(v/J).
  const auto covered = [&](double v) { return v >= A * A / J ? v * (v / A + A / J) : 2 * v * std::sqrt(v / J); };
  double vp = V;
  if (d < covered(V)) {
    const double a_reached = A * A / J;
    vp = d >= covered(a_reached) ? 0.5 * A * (std::sqrt(A * A / (J * J) + 4 * d / A) - A / J) : std::cbrt(0.25 * J * d * d);
  }
  return std::copysign(std::min(vp, V), distance);
}

double moved_goal_peak(const PeakSensitivity& d, double peak, double goal_step) noexcept {
  // peak + x with D' x + D'' x²/2 = goal_step, in the form that keeps its precision for small x.
  const double discriminant = d.slope * d.slope + 2 * d.curvature * goal_step;
  return peak + (discriminant > 0 ? 2 * goal_step / (d.slope + std::sqrt(discriminant)) : goal_step / d.slope);
}

void JerkProfile::plan(const MotionState& from, double goal, const JerkLimits& limits, double hint, PlanSlack slack) noexcept {
  evaluations_ = 0;
  // (A residual within the slack is accepted only from a plan that outlasts slack.after, so only
  // an uncertified predicted step is solved again, from where it got to, to rounding.)
  if (!plan_once(from, goal, limits, hint, true, slack)) plan_once(from, goal, limits, std::isfinite(peak_) ? peak_ : hint, false, PlanSlack{});
}

bool JerkProfile::plan_once(const MotionState& from, double goal, const JerkLimits& limits, double hint, bool predict,
                            const PlanSlack& slack) noexcept {
  loose_ = false;
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  const Bounds bounds(limits);
  start_ = {from.p, from.v, std::clamp(from.a, -A, A)};
  goal_ = goal;
  limits_ = limits;
  const double v0 = start_.v, a0 = start_.a;
  const double d = goal - from.p;
  // Reached to rounding: the last bits of the distance are what the plan's end may miss by (and
  // the plan is shifted by that onto the goal, below).
  double tolerance = 4 * DBL_EPSILON * (std::abs(from.p) + std::abs(goal)) + DBL_MIN;
  // The last two evaluations: the solve comes back to branch ends and bracket ends it has
  // evaluated, and ends on one of them (whose change the plan keeps).
  double last_vp = std::numeric_limits<double>::quiet_NaN(), earlier_vp = last_vp;
  Reach last, earlier;
  // A residual within rounding, or within the slack for a plan that lasts beyond its horizon.
  const auto close_enough = [&](const Reach& r) {
    return std::abs(r.distance) <= tolerance || (std::abs(r.distance) <= slack.distance && r.duration > slack.after);
  };
  const auto residual = [&](double vp) {
    if (vp == last_vp) return last;
    if (vp == earlier_vp) return earlier;
    ++evaluations_;
    Reach r = jerk::reach(v0, a0, vp, bounds);
    r.distance -= d;
    tolerance = 4 * DBL_EPSILON * (std::abs(from.p) + std::abs(goal) + r.magnitude) + DBL_MIN;
    if (last_vp == last_vp) earlier_vp = last_vp, earlier = last;  // (last is unset before the first)
    last_vp = vp;
    last = r;
    return r;
  };

  // D is increasing for vp beyond both the natural velocity (reached by releasing the
  // acceleration; computed exactly as velocity_change computes it) and 0; between them (a change
  // and a stop in the same direction) it may not be.
  // A natural velocity that is zero to rounding (a state braking onto rest) is zero: the two
  // branch ends coincide, and the solve next to them runs in u (below) rather than creeping up on
  // a |vp|^(3/2) root in vp.
  const double release = 0.5 * a0 * std::abs(a0) * bounds.inv_J;
  const double unsnapped = std::clamp(v0 + release, -V, V);
  const double natural = std::abs(unsnapped) <= 8 * DBL_EPSILON * std::abs(v0) ? 0.0 : unsnapped;
  const double low = std::min(natural, 0.0), high = std::max(natural, 0.0);
  // Beyond the natural velocity, away from 0, where reaching vp means reversing the
  // acceleration (the side where D has its square-root corner), D is smooth in
  // u = sqrt(|vp - natural|) with slope corner_slope at u = 0: there vp = natural ± (r/slope)².
  const double corner_slope = 2 * natural * std::sqrt(bounds.inv_J);
  const bool corner_beyond = natural != 0 && (natural > 0 ? a0 <= 0 : a0 >= 0);
  // Where the root lies by a model, from a branch end `end` (0 or the natural velocity) with
  // residual r there; `beyond`: the root lies on the far side of `end` from 0 (the corner model
  // above, when it applies). From the natural velocity (release the acceleration), or from 0
  // when the start is at rest, the rest of the distance is a move from rest: rest_to_rest_peak,
  // exact from rest. From 0 otherwise (brake to rest first), the braking change's distance is smooth
  // in vp there (slope r.slope, the change's peak acceleration staying well away from 0) and
  // the stop from vp adds vp sqrt(|vp|/J): with vp = -sign(r) y², y solves
  // sqrt(1/J) y³ + slope y² = |r|, by Newton from above (convex: monotone, 3 steps suffice for
  // a start).
  // The braking model alone: NaN where it does not apply (r not at 0, a start at rest, a root
  // beyond its range).
  const auto braking_model = [&](const Reach& r) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (natural == 0 || !(r.slope > 0) || !std::isfinite(r.slope)) return nan;
    const double target = std::abs(r.distance), k = std::sqrt(bounds.inv_J);
    // The change is linear only while J |vp| stays small next to its peak acceleration squared:
    // y up to y_valid. A root beyond that is left to the move from rest.
    const double y_valid = 0.5 * r.change.peak * k;
    if (y_valid * y_valid * (k * y_valid + r.slope) < target) return nan;
    // y_valid and the quadratic term alone both bound y from above.
    double y = std::min(y_valid, std::sqrt(target / r.slope));
    for (int i = 0; i < 3 && y > 0; ++i) y -= (y * y * (k * y + r.slope) - target) / (y * (3 * k * y + 2 * r.slope));
    return r.distance > 0 ? -y * y : y * y;
  };
  const auto model_from = [&](double end, const Reach& r, bool beyond) {
    if (end == natural && beyond && corner_beyond) {
      const double u = -r.distance / corner_slope;
      if (u > 0) return natural + (natural > 0 ? u * u : -u * u);
    }
    const double braking = end == 0 ? braking_model(r) : std::numeric_limits<double>::quiet_NaN();
    return braking == braking ? braking : end + rest_to_rest_peak(-r.distance, limits);
  };

  double vp = std::numeric_limits<double>::quiet_NaN();
  double cruise = 0;
  // Ends the solve on x when its residual r is close enough.
  const auto accept = [&](double x, const Reach& r) {
    if (!close_enough(r)) return false;
    vp = x;
    loose_ = std::abs(r.distance) > tolerance;
    return true;
  };
  // A re-plan toward the same goal from a state on the last plan has the same peak: try it
  // first, with a few Newton steps kept on its branch (so that a target that moves a little
  // each tick costs a few evaluations).
  bool predicted = false;
  // What the warm start learnt, for the bracketed solve should it not converge: on a branch
  // where D increases (beyond both 0 and the natural velocity), evaluated points below and above
  // the root bracket it; the last Newton iterate is the best start.
  double below = std::numeric_limits<double>::quiet_NaN(), f_below = 0;
  double above = std::numeric_limits<double>::quiet_NaN(), f_above = 0;
  double resume = hint;
  // Where the warm start's last Newton step (in vp) pointed when that was past both 0 and the
  // natural velocity from a branch beyond them (the goal turned back; NaN otherwise): the
  // bracketed solve then evaluates first the branch end on that side.
  double pointed = std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(hint)) {
    double previous_residual = 0;
    const double lo = hint >= high ? high : hint <= low ? -V : low;
    const double hi = hint >= high ? V : hint <= low ? low : high;
    // On a branch that starts at the natural velocity, D grows like sqrt(|vp - natural|) there
    // (a state on the stopping part of a plan has its root right at that corner): Newton runs in
    // u = sqrt(|vp - natural|), where D is smooth, as in the bracketed refinement below; at the
    // corner itself (u = 0) with corner_slope.
    const bool mapped = (lo == natural && a0 <= 0) || (hi == natural && a0 >= 0);
    // At the natural velocity itself on a smooth branch, take the branch's side of it (the
    // distance's slope there is that side's).
    double x = std::clamp(hint, lo, hi);
    if (x == natural && !mapped) x = std::nextafter(x, hint >= high ? V : -V);
    const double dir = lo == natural ? 1.0 : -1.0;
    const double u_end = mapped ? std::sqrt(hi - lo) : 0.0;
    double u = mapped ? std::sqrt(std::abs(x - natural)) : 0.0;
    const bool monotone = lo >= high || hi <= low;
    const auto points_past_both = [&](double newton) { return (lo == high && newton < low) || (hi == low && newton > high); };
    for (int k = 0; k < kMaxWarmSteps; ++k) {
      const Reach r = residual(x);
      if (monotone && r.distance < 0 && !(x <= below)) below = x, f_below = r.distance;
      if (monotone && r.distance > 0 && !(x >= above)) above = x, f_above = r.distance;
      if (std::abs(x) == V && r.distance * x <= 0) {
        vp = x;
        cruise = -r.distance / x;
        break;
      }
      if (accept(x, r)) break;
      double next = 0;
      if (mapped) {
        const double slope_u = u > 0 ? r.slope * 2 * u * dir : corner_slope;
        const double u_next = std::clamp(u - r.distance / slope_u, 0.0, u_end);
        if (!(u_next > 0)) {
          // At the corner itself: the bracketed refinement takes over, told where a step in vp
          // points (when it points across the corner).
          const double newton = x - r.distance / r.slope;
          if (u > 0 && r.slope > 0 && points_past_both(newton)) pointed = newton;
          break;
        }
        // (At the branch's far end exactly that end, which the bracketed solve may evaluate.)
        next = u_next == u_end ? (dir > 0 ? hi : lo) : std::clamp(natural + dir * u_next * u_next, lo, hi);
        u = u_next;
      } else {
        // A step that points past both 0 and the natural velocity: the root is likely on the
        // far side, whose end the bracketed solve then evaluates first. (A step that ends
        // between them is clamped to the near end, as any other: evaluating that end brackets a
        // root next to it.)
        const double newton = x - r.distance / r.slope;
        if (points_past_both(newton)) {
          pointed = newton;
          break;
        }
        next = std::clamp(newton, lo, hi);
      }
      if (!(next != x)) break;
      // Newton converges quadratically: r_next ~ K r² with K = r / r_previous² from the last
      // step. When that predicts a residual well within tolerance, take the step without
      // evaluating it; the plan's end certifies it below (else the solve runs again in full).
      // On the first step (no previous residual yet) of a plan that outlasts the slack's
      // horizon, the Taylor estimate from D'' stands in for K where it applies
      // (newton_residual). (Plans that end sooner must end on the goal to rounding, which no
      // estimate predicts reliably: a miss would cost a second solve.)
      const bool outlasts = r.duration > slack.after;
      double predicted_residual = std::numeric_limits<double>::quiet_NaN();
      if (predict && next > lo && next < hi && (k > 0 || outlasts)) {
        predicted_residual = k > 0 ? r.distance / (previous_residual * previous_residual) * r.distance * r.distance
                                   : jerk::newton_residual(r, x, next - x, bounds);
        const double allowed = outlasts ? std::max(tolerance, slack.distance) : tolerance;
        if (std::abs(predicted_residual) <= 0.25 * allowed) {
          vp = next;
          predicted = true;
          break;
        }
      }
      if (predict && k == 0 && outlasts && predicted_residual == predicted_residual) {
        // Where the Newton step's D'' step²/2 is known (the step stays inside r's regimes) but not
        // small enough on the first step, a second-order step leaves D''' step³/6. (Where it is
        // not known, the second-order step measured never inside either.)
        const SecondOrderStep second = jerk::second_order_step(r, x, bounds);
        const double to = x + second.step;
        if (to > lo && to < hi && std::abs(second.residual) <= 0.25 * std::max(tolerance, slack.distance)) {
          vp = to;
          predicted = true;
          break;
        }
      }
      previous_residual = r.distance;
      x = next;
      resume = next;
    }
  }
  if (!(vp == vp)) {
    // The branch that holds the root, bracketed as f(lo) <= 0 <= f(hi).
    double lo = 0, hi = 0, f_lo = 0, f_hi = 0;
    // The slope at a bracket end next to the root's side of 0 or the natural velocity, where
    // the residual is often far smaller than at ±V: a Newton step from there starts the solve.
    double slope_lo = 0, slope_hi = 0;
    // Between 0 and the natural velocity: where model_from puts the root, from the end nearer it.
    double model = std::numeric_limits<double>::quiet_NaN();
    // A probe that falls short of the goal on the way to `end` (V or -V): one Newton step from it
    // (it usually lands close) before `end` is evaluated. True when the step ends the solve or
    // brackets the root with the probe; otherwise a step still short becomes short_x, at_short.
    const auto step_from_probe = [&](double probe, const Reach& at_probe, double end, double& short_x, Reach& at_short) {
      const double step = at_probe.slope > 0 ? probe - at_probe.distance / at_probe.slope : probe;
      if (!((step - probe) * (step - end) < 0)) return false;
      const Reach at_step = residual(step);
      if (accept(step, at_step)) return true;
      if ((at_step.distance >= 0) != (end > 0)) {
        short_x = step, at_short = at_step;
        return false;
      }
      const bool up = step > probe;
      const Reach& r_lo = up ? at_probe : at_step;
      const Reach& r_hi = up ? at_step : at_probe;
      lo = up ? probe : step, f_lo = r_lo.distance, slope_lo = r_lo.slope;
      hi = up ? step : probe, f_hi = r_hi.distance, slope_hi = r_hi.slope;
      return true;
    };
    const bool warm_bracket = below == below && above == above;
    // high is evaluated first, unless the warm start pointed below low: then low is, and high
    // only if the root is not below low after all.
    const bool low_first = !warm_bracket && low != high && pointed < low;
    const bool root_below_low = low_first && residual(low).distance >= 0;
    const Reach at_high = warm_bracket || root_below_low ? Reach{} : residual(high);
    if (warm_bracket) {
      lo = below, f_lo = f_below, hi = above, f_hi = f_above;
    } else if (!root_below_low && at_high.distance <= 0) {
      // The root is in [high, V]. First the model: brake (or release) to `high`, then the rest
      // of the distance as a move from rest; it usually brackets the root with `high` and spares
      // the evaluation at V.
      const double probe = model_from(high, at_high, true);
      const bool probed = probe > high && probe < V;
      const Reach at_probe = probed ? residual(probe) : at_high;
      if (probed && accept(probe, at_probe)) {
        // (the probe is on the root)
      } else if (probed && at_probe.distance >= 0) {
        lo = high, f_lo = at_high.distance, slope_lo = at_high.slope;
        hi = probe, f_hi = at_probe.distance, slope_hi = at_probe.slope;
      } else {
        double short_x = probed ? probe : high;
        Reach at_short = at_probe;
        if (!(probed && step_from_probe(probe, at_probe, V, short_x, at_short))) {
          const Reach at_v = residual(V);
          if (at_v.distance <= 0) {
            vp = V;
            cruise = -at_v.distance / V;
          }
          lo = short_x, f_lo = at_short.distance, slope_lo = at_short.slope;
          hi = V, f_hi = at_v.distance;
        }
      }
    } else {
      const Reach at_low = low == high ? at_high : residual(low);
      if (at_low.distance >= 0) {
        // The root is in [-V, low]: as above, mirrored.
        const double probe = model_from(low, at_low, true);
        const bool probed = probe < low && probe > -V;
        const Reach at_probe = probed ? residual(probe) : at_low;
        if (probed && accept(probe, at_probe)) {
          // (the probe is on the root)
        } else if (probed && at_probe.distance <= 0) {
          lo = probe, f_lo = at_probe.distance, slope_lo = at_probe.slope;
          hi = low, f_hi = at_low.distance, slope_hi = at_low.slope;
        } else {
          double short_x = probed ? probe : low;
          Reach at_short = at_probe;
          if (!(probed && step_from_probe(probe, at_probe, -V, short_x, at_short))) {
            const Reach at_minus_v = residual(-V);
            if (at_minus_v.distance >= 0) {
              vp = -V;
              cruise = at_minus_v.distance / V;
            }
            lo = -V, f_lo = at_minus_v.distance;
            hi = short_x, f_hi = at_short.distance, slope_hi = at_short.slope;
          }
        }
      } else {
        lo = low, f_lo = at_low.distance, slope_lo = at_low.slope;
        hi = high, f_hi = at_high.distance, slope_hi = at_high.slope;
        // D need not be monotone here, so the end with the smaller residual need not be the
        // nearer one: the braking model, where it applies, first (it checks its own range).
        model = braking_model(low == 0 ? at_low : at_high);
        if (!(model == model))
          model = std::abs(at_low.distance) <= std::abs(at_high.distance) ? model_from(low, at_low, false) : model_from(high, at_high, false);
      }
    }
    // Safeguarded Newton: a step that leaves the bracket becomes a regula falsi or bisection.
    // Near vp = natural the distance grows like a square root of vp, so the bracket may close
    // before the residual does: an end of the bracket that falls short of the goal in the
    // direction it moves is finished exactly by a short cruise at its velocity (time-optimal but
    // for that cruise, which is accepted once negligible).
    const double negligible_s = 1e-9 * (V / A + A / J);
    const auto finish_short = [&](double x, double f) {
      if (x == 0 || -f / x < 0 || -f / x > negligible_s) return false;
      vp = x;
      cruise = -f / x;
      return true;
    };
    if (!(vp == vp) && std::abs(f_lo) <= tolerance) vp = lo;
    if (!(vp == vp) && std::abs(f_hi) <= tolerance) vp = hi;
    if (!(vp == vp) && !finish_short(lo, f_lo) && !finish_short(hi, f_hi)) {
      // Next to the natural velocity D grows like the square root of |vp - natural|: there the
      // iteration runs in u = sqrt(|vp - natural|), in which D is smooth.
      const bool mapped = !warm_bracket && ((lo == natural && a0 <= 0) || (hi == natural && a0 >= 0));
      const double dir = lo == natural ? 1.0 : -1.0;
      const auto to_vp = [&](double u) { return mapped ? natural + dir * u * u : u; };
      const auto to_u = [&](double x) { return mapped ? std::sqrt(std::abs(x - natural)) : x; };
      double u_lo = to_u(lo), u_hi = to_u(hi);
      const auto inside = [&](double u) { return (u - u_lo) * (u - u_hi) < 0; };
      const auto secant = [&] { return u_lo - f_lo * (u_hi - u_lo) / (f_hi - f_lo); };
      // The warm start's last iterate; else, between 0 and the natural velocity, the model; else
      // a Newton step from an end; else the secant.
      const bool resume_inside = (resume - lo) * (resume - hi) < 0;
      const bool model_inside = (model - lo) * (model - hi) < 0;
      double u = resume_inside ? to_u(resume) : model_inside ? to_u(model) : secant();
      if (!resume_inside && !model_inside) {
        // A Newton step from the end with the smaller residual (in u where mapped).
        const auto newton_from = [&](double x, double f, double slope) {
          const double ux = to_u(x);
          if (!(slope > 0) || !std::isfinite(slope) || (mapped && !(ux > 0))) return std::numeric_limits<double>::quiet_NaN();
          return ux - f / (mapped ? slope * 2 * ux * dir : slope);
        };
        const double start = std::abs(f_lo) <= std::abs(f_hi) ? newton_from(lo, f_lo, slope_lo) : newton_from(hi, f_hi, slope_hi);
        if (inside(start)) u = start;
      }
      if (!inside(u)) u = 0.5 * (u_lo + u_hi);
      bool bisect = false;
      double previous_x = std::numeric_limits<double>::quiet_NaN();
      for (int k = 0; k < kMaxRefinements; ++k) {
        const double x = to_vp(u);
        const Reach r = residual(x);
        if (accept(x, r)) break;
        // In u, steps can go on shrinking the bracket's far side while vp = natural ± u² no
        // longer changes at all (its last bit is reached): the residual is then as small as vp's
        // resolution allows. Accept it when the end shift below may absorb it; otherwise stop
        // (the fallback after the loop keeps the plan exact). Without this the loop ran to its
        // bound on the same vp (issue: 64 evaluations a tick on some moving-target states).
        if (x == previous_x) {
          if (std::abs(r.distance) <= kShiftable * tolerance) vp = x;
          break;
        }
        previous_x = x;
        if (r.distance < 0) {
          lo = x, u_lo = u, f_lo = r.distance;
        } else {
          hi = x, u_hi = u, f_hi = r.distance;
        }
        if (finish_short(x, r.distance)) break;
        if (std::abs(u_hi - u_lo) <= 2 * DBL_EPSILON * std::max(std::abs(u_lo), std::abs(u_hi))) break;
        double next = u - r.distance / (mapped ? r.slope * 2 * u * dir : r.slope);
        if (!inside(next) || next == u) {
          next = bisect ? 0.5 * (u_lo + u_hi) : secant();
          if (!inside(next)) next = 0.5 * (u_lo + u_hi);
          bisect = !bisect;
        }
        u = next;
      }
      if (!(vp == vp) && lo > 0) {
        vp = lo;
        cruise = -f_lo / lo;
      } else if (!(vp == vp) && hi < 0) {
        vp = hi;
        cruise = -f_hi / hi;
      } else if (!(vp == vp)) {
        vp = 0.5 * (lo + hi);
      }
    }
  }
  peak_ = vp;

  const bool evaluated = vp == last_vp || vp == earlier_vp;
  const Reach& ended_on = vp == last_vp ? last : earlier;
  const VelocityChange change = evaluated ? ended_on.change : jerk::velocity_change(v0, a0, vp, bounds);
  const double m = jerk::stop_peak(vp, bounds);
  stop_peak_ = m;
  inverse_acceleration_ = bounds.inv_A;
  inverse_jerk_ = bounds.inv_J;
  const double stop_jerk = vp > 0 ? -J : J;
  const double stop_ramp = m / J;
  const double stop_hold = m > 0 ? std::max(0.0, std::abs(vp) / m - m / J) : 0.0;
  pieces_ = {Piece{change.rise, change.s * J},   Piece{change.hold, 0},     Piece{change.fall, -change.s * J},
             Piece{cruise, 0},                   Piece{stop_ramp, stop_jerk}, Piece{stop_hold, 0},
             Piece{stop_ramp, -stop_jerk}};
  // (Summed from the values, not read back from pieces_ just stored.)
  duration_ = ((change.rise + change.hold) + (change.fall + cruise)) + ((stop_ramp + stop_hold) + stop_ramp);
  // The plan's end misses the goal by the solve's last bits: shift the whole plan onto the goal,
  // so that the position's rounding never accumulates from tick to tick (a shift larger than
  // rounding, from a solve that did not converge, is left for the next plan to correct).
  // Where the solve ended on an evaluation, its residual is the miss (to rounding); a predicted
  // step is certified by following the plan to its end.
  // A predicted step in a plan that lasts beyond the slack's horizon is taken as it is (its end
  // is within the slack by the prediction, and is never reached).
  if (predicted && slack.distance > 0 && duration_ > slack.after) {
    loose_ = true;
    offset_ = 0;
    return true;
  }
  const double miss = evaluated && !predicted ? -ended_on.distance - cruise * vp : goal - follow(duration_).p;
  if (predicted && !(std::abs(miss) <= kCertified * tolerance)) return false;
  // (A plan that ends within its slack is not shifted: shifts that come and go from tick to
  // tick would add their size to the commands' third differences.)
  offset_ = !loose_ && std::abs(miss) <= kShiftable * tolerance ? miss : 0.0;
  return true;
}

PeakSensitivity JerkProfile::peak_sensitivity(double t) const noexcept {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Bounds k(limits_, inverse_acceleration_, inverse_jerk_);
  const double vp = peak_;
  const double fall_start = pieces_[0].duration + pieces_[1].duration, fall_end = fall_start + pieces_[2].duration;
  if (pieces_[3].duration > 0 || vp == 0 || !(t < fall_end)) return {nan, nan, false};
  // reach()'s slopes, with the change's peak acceleration as seen from that state: the same until
  // the fall, then what is left of it.
  const double s = pieces_[0].jerk > 0 ? 1.0 : -1.0;
  const bool holds = t <= fall_start && pieces_[1].duration > 0;
  const double m = holds ? k.A : k.J * (fall_end - std::max(t, fall_start));
  const double ms = stop_peak_;
  PeakSensitivity out;
  out.slope = jerk::change_slope(s, vp, m, k) + jerk::stop_slope(jerk::stop_coast(std::abs(vp), ms, ms >= k.A, k), ms, k);
  out.curvature = jerk::change_curvature(s, vp, m, holds, k) + jerk::stop_curvature(vp, ms, k);
  out.before_fall = t <= fall_start;
  return out;
}

MotionState JerkProfile::at(double t) const noexcept {
  if (!(t < duration_)) return {goal_, 0, 0};
  MotionState s = follow(t);
  s.p += offset_;
  return s;
}

MotionState JerkProfile::follow(double t) const noexcept {
  MotionState s = start_;
  for (std::size_t i = 0; i < kPieces; ++i) {
    if (t <= pieces_[i].duration) return advance(s, t, pieces_[i].jerk);
    s = advance(s, pieces_[i].duration, pieces_[i].jerk);
    t -= pieces_[i].duration;
    // The stop was planned from exactly (peak, 0): do not carry the change's rounding into it.
    if (i == 2 || i == 3) s.v = peak_, s.a = 0;
  }
  return s;
}

}  // namespace avar::control
