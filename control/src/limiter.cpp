#include "avar/control/limiter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::control {
namespace {

std::size_t ticks_at_least(double seconds, double dt) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(seconds / dt - 1e-9)));
}

}  // namespace

void Limiter::MovingAverage::fill(double v) noexcept {
  std::fill(ring.begin(), ring.end(), v);
  sum = v * static_cast<double>(ring.size());
  next = 0;
}

double Limiter::MovingAverage::push(double v) noexcept {
  sum += v - ring[next];
  ring[next] = v;
  if (++next == ring.size()) {
    next = 0;
    sum = 0;
    for (double x : ring) sum += x;
  }
  return sum / static_cast<double>(ring.size());
}

double Limiter::DelayLine::push(double v) noexcept {
  if (ring.empty()) return v;
  const double out = ring[next];
  ring[next] = v;
  next = next + 1 == ring.size() ? 0 : next + 1;
  return out;
}

Limiter::Limiter(std::vector<ChannelLimits> limits, double dt_s) : dt_s_(dt_s), last_(limits.size(), 0.0) {
  if (!(dt_s > 0)) throw std::invalid_argument("the limiter needs a positive tick period");
  std::size_t longest = 0;
  for (const ChannelLimits& l : limits) {
    if (!(l.max > l.min) || !(l.max_velocity > 0) || !(l.max_acceleration > 0) || !(l.max_jerk > 0) || !(l.soft_margin >= 0))
      throw std::invalid_argument("channel limits must be positive, with max > min");
    Channel c;
    c.limits = l;
    // The first average's acceleration is the rate-limited velocity's change over N1 ticks (kept
    // within V) divided by N1 dt; the second's jerk is the acceleration's change over N2 ticks
    // (at most 2A, a reversal) divided by N2 dt.
    const std::size_t n1 = ticks_at_least(l.max_velocity / l.max_acceleration, dt_s);
    const double a_bound = l.max_velocity / (static_cast<double>(n1) * dt_s);
    const std::size_t n2 = ticks_at_least(2 * std::min(a_bound, l.max_acceleration) / l.max_jerk, dt_s);
    c.past_velocity.ring.assign(n1, 0.0);
    c.acceleration_stage.ring.assign(n1, 0.0);
    c.jerk_stage.ring.assign(n2, 0.0);
    c.settle_ticks = n1 + n2;
    longest = std::max(longest, (n1 - 1) + (n2 - 1));
    channels_.push_back(std::move(c));
  }
  // Each average delays by (N - 1)/2 ticks; pad every channel to the longest delay, rounded up
  // to whole ticks so that the padding is a plain ring.
  const std::size_t common = (longest + 1) / 2;
  for (Channel& c : channels_) {
    const std::size_t own2 = (c.acceleration_stage.ring.size() - 1) + (c.jerk_stage.ring.size() - 1);  // twice the delay
    c.padding.ring.assign((2 * common - own2) / 2, 0.0);
    c.goal_delay.ring.assign(common, 0.0);
    c.settle_ticks += c.padding.ring.size();
  }
  delay_s_ = static_cast<double>(common) * dt_s;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const ChannelLimits& l = channels_[i].limits;
    const double start = std::clamp(0.0, l.min, l.max);
    last_[i] = start;
  }
  reset(last_);
}

void Limiter::reset(std::span<const double> pose) noexcept {
  for (std::size_t i = 0; i < channels_.size() && i < pose.size(); ++i) {
    if (!std::isfinite(pose[i])) continue;
    Channel& c = channels_[i];
    const double p = std::clamp(pose[i], c.limits.min, c.limits.max);
    c.goal = c.rate_limited = last_[i] = p;
    c.acceleration_stage.fill(p);
    c.jerk_stage.fill(p);
    c.padding.fill(p);
    c.past_velocity.fill(0.0);
    c.goal_delay.fill(p);
    c.steady_ticks = c.settle_ticks;
  }
}

bool Limiter::settled() const noexcept {
  for (const Channel& c : channels_)
    if (c.steady_ticks < c.settle_ticks || c.rate_limited != c.goal) return false;
  return true;
}

Status Limiter::apply(std::span<const double> target, std::span<double> out) noexcept {
  Status status = Status::ok;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    Channel& c = channels_[i];
    const ChannelLimits& l = c.limits;
    if (std::isfinite(target[i])) {
      const double mid = 0.5 * (l.min + l.max);
      const double lo = std::min(l.min + l.soft_margin, mid);
      const double hi = std::max(l.max - l.soft_margin, mid);
      if (target[i] < lo || target[i] > hi) ++c.clamped;
      c.goal = std::clamp(target[i], lo, hi);
    } else {
      status = Status::not_finite;
    }
    // The velocity window always holds 0 (the past velocity is within [-V, V]), so the channel
    // can always stop: it never has to pass its goal.
    const double v_past = c.past_velocity.ring[c.past_velocity.next];
    const double v_lo = std::max(-l.max_velocity, v_past - l.max_velocity);
    const double v_hi = std::min(l.max_velocity, v_past + l.max_velocity);
    const double moved = std::clamp(c.goal, c.rate_limited + v_lo * dt_s_, c.rate_limited + v_hi * dt_s_);
    c.past_velocity.push((moved - c.rate_limited) / dt_s_);
    c.steady_ticks = moved == c.rate_limited ? c.steady_ticks + 1 : 0;
    c.rate_limited = moved;
    double command = c.padding.push(c.jerk_stage.push(c.acceleration_stage.push(moved)));
    // Once every stage holds the same value the average is that value: make it exact, so a
    // held target is reached to the last bit rather than to rounding.
    if (c.steady_ticks >= c.settle_ticks) command = moved;
    command = std::clamp(command, l.min, l.max);  // rounding only: the average stays in range
    c.max_lag = std::max(c.max_lag, std::abs(c.goal_delay.push(c.goal) - command));
    last_[i] = command;
    out[i] = command;
  }
  return status;
}

}  // namespace avar::control
