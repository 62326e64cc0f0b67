#pragma once
// Per-channel motion limits applied to every command before it reaches a link.
//
// Each channel's target is clamped into its range less the soft margins and rate-limited: the
// velocity stays within [-V, V] and within V of its value N1 ticks earlier (so it can always
// stop, and never has to pass its goal). Two moving averages, of N1 and N2 ticks, then smooth it.
// A moving average never leaves the range of what it averages, so no command passes the clamped
// target or the range. The first average's acceleration is the velocity change over N1 ticks
// divided by N1 dt, at most V/(N1 dt) = A; the second's jerk is the acceleration change over N2
// ticks, at most 2A/(N2 dt) = J. A rest-to-rest move takes d/V + V/A + 2A/J: the time-optimal
// jerk-limited profile's d/V + V/A + A/J plus one jerk phase. A held target is reached exactly.
// The averages delay the motion by a fixed time; every channel is padded to the same delay,
// delay(), so channels that move together in the show stay together on the figure.
// Sized once for a tick period; apply() is real-time safe (no allocation, exception or lock).

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "avar/core/status.hpp"

namespace avar::control {

struct ChannelLimits {
  double min = 0;               ///< hard range, channel units
  double max = 1;               ///< > min
  double max_velocity = 1;      ///< units/s, > 0
  double max_acceleration = 1;  ///< units/s², > 0
  double max_jerk = 1;          ///< units/s³, > 0
  double soft_margin = 0;       ///< targets stay this far inside [min, max], units, >= 0
};

class Limiter {
 public:
  /// dt_s: the tick period every apply() will use. Throws std::invalid_argument for
  /// non-positive limits or period.
  Limiter(std::vector<ChannelLimits> limits, double dt_s);

  /// Sets the present pose, at rest. Values are clamped into range; non-finite ones keep the
  /// previous value.
  void reset(std::span<const double> pose) noexcept;

  /// One tick toward `target`: out[i] is the new command. A non-finite target keeps heading for
  /// that channel's previous goal and the call returns Status::not_finite. target and out may
  /// alias.
  Status apply(std::span<const double> target, std::span<double> out) noexcept;

  /// How long after a target is given its motion reaches the commands (seconds), the same for
  /// every channel.
  double delay() const noexcept { return delay_s_; }
  /// True when every channel's command has come to rest on its goal.
  bool settled() const noexcept;

  std::size_t size() const noexcept { return channels_.size(); }
  const ChannelLimits& limits(std::size_t channel) const noexcept { return channels_[channel].limits; }
  /// The commands of the last tick.
  std::span<const double> last() const noexcept { return last_; }
  /// The rate-limited target of the last tick (where the commands are heading).
  double heading(std::size_t channel) const noexcept { return channels_[channel].rate_limited; }
  /// Samples whose target lay outside the range less its margins.
  std::uint64_t clamped(std::size_t channel) const noexcept { return channels_[channel].clamped; }
  /// Largest distance between the (clamped) target, taken delay() earlier, and the command:
  /// how far the limits made the figure trail the show.
  double max_lag(std::size_t channel) const noexcept { return channels_[channel].max_lag; }

 private:
  /// A moving average over a ring buffer with a running sum (recomputed exactly once per lap,
  /// so rounding never accumulates).
  struct MovingAverage {
    std::vector<double> ring;
    std::size_t next = 0;
    double sum = 0;
    void fill(double v) noexcept;
    double push(double v) noexcept;
  };
  /// A pure delay of ring.size() ticks (none when empty).
  struct DelayLine {
    std::vector<double> ring;
    std::size_t next = 0;
    void fill(double v) noexcept { std::fill(ring.begin(), ring.end(), v); }
    double push(double v) noexcept;
  };
  struct Channel {
    ChannelLimits limits;
    double goal = 0;          ///< clamped target
    double rate_limited = 0;  ///< after the velocity limit
    DelayLine past_velocity;  ///< the rate-limited velocity N1 ticks ago
    MovingAverage acceleration_stage;
    MovingAverage jerk_stage;
    DelayLine padding;        ///< up to the common delay
    DelayLine goal_delay;     ///< the goal as it was delay() ago, for the lag figure
    std::uint64_t steady_ticks = 0;  ///< ticks the rate-limited value has not changed
    std::size_t settle_ticks = 0;    ///< ticks after which the output equals a steady input
    std::uint64_t clamped = 0;
    double max_lag = 0;
  };

  double dt_s_;
  double delay_s_ = 0;
  std::vector<Channel> channels_;
  std::vector<double> last_;
};

}  // namespace avar::control
