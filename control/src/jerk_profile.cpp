#include "avar/control/jerk_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "jerk_bounds.hpp"
#include "jerk_bracket.hpp"
#include "jerk_branches.hpp"
#include "jerk_reach.hpp"
#include "jerk_refine.hpp"
#include "jerk_residuals.hpp"
#include "jerk_stop.hpp"
#include "jerk_velocity_change.hpp"
#include "jerk_warm_start.hpp"

namespace avar::control {
namespace {

using jerk::Bounds;

/// A plan taken on a predicted Newton step must end this close to the goal (in tolerances).
constexpr double kCertified = 4;
static_assert(JerkProfile::kMaxEvaluations == 2 * jerk::kMaxWarmSteps + 3 + jerk::kMaxRefinements);

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
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  const Bounds bounds(limits);
  start_ = {from.p, from.v, std::clamp(from.a, -A, A)};
  goal_ = goal;
  limits_ = limits;
  const double v0 = start_.v, a0 = start_.a;
  jerk::Residuals residual(start_, goal, bounds, slack, evaluations_);
  const jerk::Branches branches(v0, a0, V, bounds);
  jerk::Solution solution;
  const jerk::WarmStart warm = jerk::warm_start(hint, predict, slack, V, branches, bounds, residual, solution);
  if (!solution.found()) {
    const jerk::Bracket bracket = jerk::bracket_root(warm, V, limits, branches, bounds, residual, solution);
    jerk::refine(bracket, warm.resume, 1e-9 * (V / A + A / J), branches, residual, solution);
  }
  const double vp = solution.vp, cruise = solution.cruise;
  const bool predicted = solution.predicted;
  loose_ = solution.loose;
  const double tolerance = residual.tolerance();
  peak_ = vp;

  const bool evaluated = residual.remembers(vp);
  const jerk::Reach& ended_on = residual.remembered(vp);
  const jerk::VelocityChange change = evaluated ? ended_on.change : jerk::velocity_change(v0, a0, vp, bounds);
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
  offset_ = !loose_ && std::abs(miss) <= jerk::kShiftable * tolerance ? miss : 0.0;
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
