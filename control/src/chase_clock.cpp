#include "avar/control/chase_clock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace avar::control {
namespace {

constexpr double kChaseMaxRateError = 0.1;  // the filtered rate stays within 10% of play speed
constexpr double kChaseStaleFrames = 2.5;   // no new position for this many frames: freewheeling

}  // namespace

const char* to_string(ChaseState s) noexcept {
  switch (s) {
    case ChaseState::waiting: return "waiting";
    case ChaseState::locked: return "locked";
    case ChaseState::freewheeling: return "freewheeling";
    case ChaseState::stopped: return "stopped";
  }
  return "?";
}

ChaseClock::ChaseClock(inputs::TimecodeSource& source, ChaseOptions options, std::int64_t (*clock_ns)() noexcept)
    : source_(source), options_(options), clock_ns_(clock_ns) {}

ShowClockReading ChaseClock::read(double now_s) noexcept {
  if (!clock_ns_) source_.advance_to(static_cast<std::int64_t>(std::llround(now_s * 1e9)));
  const double t = clock_ns_ ? static_cast<double>(clock_ns_()) * 1e-9 : now_s;
  clock_s_ = t;
  error_s_ = std::numeric_limits<double>::quiet_NaN();
  if (state_ == ChaseState::stopped) return {std::max(0.0, phase_s_ - options_.offset_s), true};

  const inputs::TimecodeReading r = source_.latest();
  const double direction = r.reverse ? -1.0 : 1.0;
  const double arrival_s = static_cast<double>(r.arrival_ns) * 1e-9;
  const bool fresh =
      r.sequence != seen_sequence_ && r.sequence != 0 && (state_ == ChaseState::waiting || r.seconds != last_position_s_);
  if (r.sequence != seen_sequence_) seen_sequence_ = r.sequence;

  // The chase clock now, at its filtered rate.
  if (state_ != ChaseState::waiting) phase_s_ += rate_ * (t - update_at_s_);
  update_at_s_ = t;

  if (fresh) {
    frame_s_ = 1.0 / frames_per_second(r.rate);
    const double source_now = r.seconds + direction * (t - arrival_s);
    const double e = source_now - phase_s_;
    if (state_ == ChaseState::waiting && options_.offset_label) {
      Timecode label = *options_.offset_label;
      label.rate = r.rate;
      label.frames = std::min(label.frames, nominal_fps(r.rate) - 1);
      if (!valid(label)) label.frames = 2;  // a dropped drop-frame label: the minute's first frame
      options_.offset_s =
          to_seconds(label) + static_cast<double>(options_.offset_label->frames - label.frames) / frames_per_second(r.rate);
    }
    if (state_ == ChaseState::waiting || std::abs(e) > options_.jump_s) {
      if (state_ != ChaseState::waiting) ++jumps_;
      phase_s_ = source_now;
      rate_ = direction;
    } else {
      // Critically damped second-order loop, gains per update; the rate term is per second of
      // time since the previous new position.
      const double interval = std::max(t - fresh_at_s_, 1e-3);
      const double beta = options_.alpha * options_.alpha / 4.0;
      phase_s_ += options_.alpha * e;
      rate_ = std::clamp(rate_ + beta * e / interval, direction - kChaseMaxRateError, direction + kChaseMaxRateError);
    }
    last_position_s_ = r.seconds;
    fresh_at_s_ = std::max(arrival_s, fresh_at_s_);
    state_ = ChaseState::locked;
  }

  if (state_ == ChaseState::waiting) return {0.0, false};
  const double silent_s = t - fresh_at_s_;
  if (silent_s > options_.freewheel_s) {
    state_ = ChaseState::stopped;
    return {std::max(0.0, phase_s_ - options_.offset_s), true};
  }
  if (silent_s > kChaseStaleFrames * frame_s_) {
    state_ = ChaseState::freewheeling;
  } else {
    state_ = ChaseState::locked;
    error_s_ = phase_s_ - (r.seconds + direction * (t - arrival_s));
    errors_.record(static_cast<std::int64_t>(std::llround(std::abs(error_s_) * 1e9)));
    if (std::abs(error_s_) > std::abs(worst_s_)) worst_s_ = error_s_;
  }
  return {std::max(0.0, phase_s_ - options_.offset_s), false};
}

}  // namespace avar::control
