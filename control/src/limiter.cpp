#include "avar/control/limiter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::control {

Limiter::Limiter(std::vector<ChannelLimits> limits, double dt_s) : dt_s_(dt_s), plans_(limits.size()), last_(limits.size(), 0.0) {
  if (!(dt_s > 0)) throw std::invalid_argument("the limiter needs a positive tick period");
  for (const ChannelLimits& l : limits) {
    if (l.digital) {
      if (!(l.max > l.min)) throw std::invalid_argument("a digital channel needs max > min");
      Channel c;
      c.limits = l;
      channels_.push_back(c);
      continue;
    }
    if (!(l.max > l.min) || !(l.max_velocity > 0) || !(l.max_acceleration > 0) || !(l.max_jerk > 0) || !(l.soft_margin >= 0))
      throw std::invalid_argument("channel limits must be positive, with max > min");
    Channel c;
    c.limits = l;
    c.jerk_limits = own_limits(l);
    // The distance a rest-to-rest move needs to reach full speed, or the range if shorter.
    const double scale = l.max_velocity * (l.max_velocity / l.max_acceleration + l.max_acceleration / l.max_jerk);
    c.slack = 1e-9 * std::min(scale, l.max - l.min);
    channels_.push_back(c);
  }
  for (std::size_t i = 0; i < channels_.size(); ++i) last_[i] = std::clamp(0.0, channels_[i].limits.min, channels_[i].limits.max);
  reset(last_);
}

void Limiter::reset(std::span<const double> pose) noexcept {
  for (std::size_t i = 0; i < channels_.size() && i < pose.size(); ++i) {
    if (!std::isfinite(pose[i])) continue;
    Channel& c = channels_[i];
    const double p = c.limits.digital ? switched(c.limits, pose[i]) : std::clamp(pose[i], c.limits.min, c.limits.max);
    c.goal = last_[i] = p;
    c.state = {p, 0, 0};
    c.peak_velocity = 0;
    c.planned_ticks = 0;
    c.follows = false;
    c.on_rest_curve = false;
    c.goal_step = c.previous_goal_step = 0;
    c.gliding = false;
    c.jerk_limits = own_limits(c.limits);
  }
}

double Limiter::goal_of(const ChannelLimits& l, double target) noexcept {
  const double mid = 0.5 * (l.min + l.max);
  return std::clamp(target, std::min(l.min + l.soft_margin, mid), std::max(l.max - l.soft_margin, mid));
}

double Limiter::switched(const ChannelLimits& l, double target) noexcept {
  return target >= 0.5 * (l.min + l.max) ? l.max : l.min;
}

double Limiter::glide_duration(std::span<const double> goal, std::span<const double> peak_speed, double min_duration_s) const noexcept {
  double duration = min_duration_s;
  for (std::size_t i = 0; i < channels_.size() && i < goal.size(); ++i) {
    const Channel& c = channels_[i];
    if (!std::isfinite(goal[i]) || c.limits.digital) continue;
    const double d = std::abs(goal_of(c.limits, goal[i]) - c.state.p);
    const double speed = i < peak_speed.size() && peak_speed[i] > 0 ? std::min(peak_speed[i], c.limits.max_velocity) : c.limits.max_velocity;
    // Peak speed 2d/T, peak acceleration 8d/T², jerk 32d/T³, each within its limit.
    duration = std::max({duration, 2 * d / speed, std::sqrt(8 * d / c.limits.max_acceleration), std::cbrt(32 * d / c.limits.max_jerk)});
  }
  return duration;
}

void Limiter::glide_to(std::span<const double> goal, double duration_s) noexcept {
  if (!(duration_s > 0)) return;
  const double cube = duration_s * duration_s * duration_s;
  for (std::size_t i = 0; i < channels_.size() && i < goal.size(); ++i) {
    Channel& c = channels_[i];
    if (!std::isfinite(goal[i]) || c.limits.digital || c.state.v != 0 || c.state.a != 0) continue;
    const double to = goal_of(c.limits, goal[i]);
    const double jerk = std::min(32 * std::abs(to - c.state.p) / cube, c.limits.max_jerk);
    if (!(jerk > 0)) continue;
    // With only the jerk limit binding (2d/T <= V and 8d/T² <= A: the duration allows them), the
    // time-optimal rest-to-rest move is jerk +J, -J, -J, +J for T/4 each.
    c.jerk_limits.jerk = jerk;
    c.gliding = true;
    c.glide_goal = to;
  }
}

double Limiter::heading(std::size_t channel) const noexcept {
  const Channel& c = channels_[channel];
  return c.gliding ? std::clamp(stopping_point(c.state, own_limits(c.limits)), c.limits.min, c.limits.max) : c.goal;
}

void Limiter::warm(std::span<const double> target) noexcept {
  for (std::size_t i = 0; i < channels_.size() && i < target.size(); ++i) {
    Channel& c = channels_[i];
    if (!std::isfinite(target[i]) || c.limits.digital || c.state.v != 0 || c.state.a != 0) continue;
    const double goal = goal_of(c.limits, target[i]);
    if (goal == c.state.p) continue;
    // (Into the channel's stored plan, which a channel at rest never follows: it plans again.)
    plans_[i].plan(c.state, goal, c.jerk_limits, rest_to_rest_peak(goal - c.state.p, c.jerk_limits), {0, 2 * dt_s_});
    c.follows = false;
  }
}

bool Limiter::settled() const noexcept {
  for (const Channel& c : channels_)
    if (c.state.p != c.goal || c.state.v != 0 || c.state.a != 0) return false;
  return true;
}

double Limiter::first_guess(const Channel& c) noexcept {
  const JerkLimits& k = c.jerk_limits;
  // From rest: the rest-to-rest move's peak, exact.
  if (c.state.v == 0 && c.state.a == 0) return rest_to_rest_peak(c.goal - c.state.p, k);
  // Leaving rest, every time-optimal plan from rest in one direction starts the same way (jerk
  // toward the goal, then a hold at the acceleration limit), until its velocity change's fall.
  // While the state has stayed on that common start, the plan from it is the rest of the plan
  // from where the channel left rest: its peak is that rest-to-rest move's, exact.
  if (c.on_rest_curve && (c.goal - c.rest_origin) * c.rest_direction > 0) return rest_to_rest_peak(c.goal - c.rest_origin, k);
  // Otherwise a goal that has been moving since the channel left rest (the first plans ended
  // within a tick or two): the peaks so far extrapolated by a line (the peak before the first
  // plan was 0, at rest).
  if (c.goal_moved && c.planned_ticks == 1) return 2 * c.peak_velocity;
  if (c.goal_moved && c.planned_ticks == 2) return 2 * c.peak_velocity - c.previous_peak;
  // A state on a plan re-plans to the same plan, so the last plan's residual at its peak, from
  // where it led, is minus the goal's move this tick. While that state is before its change's
  // fall, the plan from it is the rest of the last one, with the same D' and D'' at the peak: a
  // second-order step by the goal's move then leaves an error of third order in it, also where
  // the goal's motion changes abruptly (at a key, or where a loop wraps).
  const PeakSensitivity& d = c.sensitivity;
  const bool known = d.slope > 0 && std::isfinite(d.slope);
  // Otherwise, extrapolate a smooth run of peaks (the last two steps alike) that was
  // extrapolated well last time. Near reversals and where plans change branch the peak jumps:
  // there a Newton step by the goal's move guesses better. (In the fall D' grows without bound
  // toward the corner, which makes that step the poorer guess on a smooth run.)
  const double step = c.peak_velocity - c.previous_peak, step_before = c.previous_peak - c.earlier_peak;
  const bool smooth = c.planned_ticks >= 3 && std::abs(step - step_before) <= 0.5 * std::max(std::abs(step), std::abs(step_before));
  double guess = c.peak_velocity;
  if (known && d.before_fall) {
    // (Where the first-order step alone would reverse or more than double the peak, it is kept:
    // the goal turns the plan, which the check below catches; the second-order step there can
    // land next to the last peak, on the wrong branch.)
    const double newton = c.peak_velocity + c.goal_step / d.slope;
    guess = std::abs(newton - c.peak_velocity) > std::abs(c.peak_velocity) ? newton : moved_goal_peak(d, c.peak_velocity, c.goal_step);
  } else if (c.extrapolate && smooth) {
    guess = extrapolated_peak(c);
  } else if (known) {
    guess += c.goal_step / d.slope;
  }
  // A guess that reverses or more than doubles the peak, or a plan already past its change whose
  // run of peaks broke while its goal moved back, or slowed down as it brakes: the plan turns
  // near rest (a goal that stops, and may turn back, as where homing hands over to the show),
  // where D is far from linear. Braking to rest and then moving from rest models it better. (A
  // goal still speeding up, as where homing starts, is not stopping.)
  const bool slowing = std::abs(c.goal_step) <= std::abs(c.previous_goal_step);
  const bool turning = !known && !(c.extrapolate && smooth) && (c.goal_step * c.peak_velocity < 0 || (slowing && c.state.a * c.peak_velocity < 0));
  if (turning || std::abs(guess - c.peak_velocity) > std::abs(c.peak_velocity)) return rest_to_rest_peak(c.goal - stopping_point(c.state, k), k);
  return guess;
}

void Limiter::settle(Channel& c, const MotionState& next) noexcept {
  // Rounding only: a plan stays within the range, and is finite from a finite state.
  if (std::isfinite(next.p) && std::isfinite(next.v) && std::isfinite(next.a))
    c.state = {std::clamp(next.p, c.limits.min, c.limits.max), next.v, next.a};
  else
    c.state = {c.state.p, 0, 0}, c.follows = false;
}

double Limiter::extrapolated_peak(const Channel& c) noexcept {
  // While the target moves smoothly the peak does too: the last three plans' peaks extrapolated
  // by a parabola (meaningful once planned_ticks >= 3).
  return 3 * (c.peak_velocity - c.previous_peak) + c.earlier_peak;
}

Status Limiter::apply(std::span<const double> target, std::span<double> out) noexcept {
  Status status = Status::ok;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    Channel& c = channels_[i];
    const ChannelLimits& l = c.limits;
    if (l.digital) {
      // Switches on the tick the target crosses the middle; a non-finite target keeps its goal.
      if (std::isfinite(target[i])) {
        if (target[i] < l.min || target[i] > l.max) ++c.clamped;
        c.goal = switched(l, target[i]);
      } else {
        status = Status::not_finite;
      }
      c.state = {c.goal, 0, 0};
      c.evaluations = 0;
      last_[i] = out[i] = c.goal;
      continue;
    }
    if (std::isfinite(target[i])) {
      const double goal = goal_of(l, target[i]);
      if (goal != target[i]) ++c.clamped;
      c.goal_moved = goal != c.goal;
      c.previous_goal_step = c.goal_step;
      c.goal_step = goal - c.goal;
      c.goal = goal;
      if (c.gliding && goal != c.glide_goal) {
        c.gliding = false;
        c.jerk_limits = own_limits(l);
        c.on_rest_curve = false;  // (that start was the glide's, under its lower jerk)
      }
    } else {
      c.goal_moved = false;
      c.previous_goal_step = c.goal_step;
      c.goal_step = 0;
      status = Status::not_finite;
    }
    c.evaluations = 0;
    if (c.state.p != c.goal || c.state.v != 0 || c.state.a != 0) {
      JerkProfile& profile = plans_[i];
      if (!c.goal_moved && c.follows) {
        // A held goal: the plan from a state on the last plan is the rest of it, so follow that
        // plan instead of solving it again (a plan that ends on its goal only within the slack
        // is solved again: its end is never reached).
        c.elapsed += dt_s_;
        c.earlier_peak = c.previous_peak;
        c.previous_peak = c.peak_velocity;
        ++c.planned_ticks;
        settle(c, profile.at(c.elapsed));
      } else {
        plan(c, profile);
      }
    } else {
      c.planned_ticks = 0;
    }
    c.max_lag = std::max(c.max_lag, std::abs(c.goal - c.state.p));
    last_[i] = c.state.p;
    out[i] = c.state.p;
  }
  return status;
}

// (Inlined into apply(), its only caller: as a call it cost about 1% of the limiter.)
[[gnu::always_inline]] inline void Limiter::plan(Channel& c, JerkProfile& profile) noexcept {
  const ChannelLimits& l = c.limits;
  if (c.elapsed > dt_s_) {
    // (Followed since the last solve: where the state now is along that plan.)
    c.sensitivity = profile.peak_sensitivity(c.elapsed);
    c.on_rest_curve = c.on_rest_curve && c.sensitivity.before_fall;
  }
  // Plans that last beyond two ticks may end a billionth of the channel's scale of motion
  // from the goal (never nearer a position limit than half the goal is), which saves a Newton
  // step or two; the next tick plans again from where this one got to.
  const double edge = std::min(c.goal - l.min, l.max - c.goal);
  const bool from_rest = c.state.v == 0 && c.state.a == 0;
  if (from_rest) c.rest_origin = c.state.p, c.rest_direction = c.goal > c.state.p ? 1 : -1;
  // (Not while gliding: a glide's jerk is low, and an end off the goal by the slack would
  // take a tail of ticks to make up, as the time to move a distance x grows like cbrt(x/J).)
  const double slack = c.gliding ? 0.0 : std::min(c.slack, 0.5 * edge);
  profile.plan(c.state, c.goal, c.jerk_limits, first_guess(c), {slack, 2 * dt_s_});
  // Near reversals and where the plan changes branch the peak jumps: extrapolate next time
  // only if that would have guessed this plan's peak better than the last peak did.
  c.extrapolate = c.planned_ticks < 3 ||
                  std::abs(extrapolated_peak(c) - profile.peak_velocity()) < std::abs(c.peak_velocity - profile.peak_velocity());
  c.earlier_peak = c.previous_peak;
  c.previous_peak = c.peak_velocity;
  ++c.planned_ticks;
  const MotionState next = profile.at(dt_s_);
  c.peak_velocity = profile.peak_velocity();
  c.sensitivity = profile.peak_sensitivity(dt_s_);
  // (It stays there while each plan speeds up the same way and is still before its fall.)
  c.on_rest_curve = (from_rest || c.on_rest_curve) && profile.peak_velocity() * c.rest_direction > 0 && profile.speeds_up() &&
                    c.sensitivity.before_fall;
  c.evaluations = profile.evaluations();
  c.elapsed = dt_s_;
  c.follows = profile.ends_on_goal();
  settle(c, next);
}

}  // namespace avar::control
