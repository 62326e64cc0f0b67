#pragma once
// Blinks over time (BlinkSpec): a seeded schedule of blink events, each one or two blinks.
// Construction allocates; closure() and sample() are real-time safe. Times must not go back.

#include <cstdint>
#include <span>

#include "avar/playback/runtime/behaviour_random.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

class BlinkGenerator {
 public:
  /// `limits`: one per frame channel; the close and open times are stretched so that no lid's
  /// move needs more than 90 % of its velocity, acceleration or jerk limit.
  BlinkGenerator(const BlinkSpec& spec, std::span<const IdleChannelLimits> limits, std::uint64_t seed);

  /// How shut the lids are at time t (s): 0 open, 1 closed.
  double closure(double t) noexcept;
  /// Writes every lid's value at time t into frame.
  void sample(double t, std::span<double> frame) noexcept;

  /// The close, hold and open times in use (after stretching), s.
  double close_s() const noexcept { return close_s_; }
  double open_s() const noexcept { return open_s_; }
  double blink_s() const noexcept { return close_s_ + spec_.hold_s + open_s_; }

 private:
  double one_blink(double since_start) const noexcept;
  void schedule_after(double start) noexcept;

  BlinkSpec spec_;
  BehaviourRandom random_;
  double close_s_ = 0, open_s_ = 0;
  double event_start_ = 0;  ///< the current (or next) event
  bool event_double_ = false;
};

}  // namespace avar::playback
