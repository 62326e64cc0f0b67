#pragma once
// The device's motion limiter: every output the device commands has passed it. Per control tick
// it moves a channel's position toward its target (following the target's own motion) with at
// most the channel's speed, changes the
// speed by at most its acceleration, and never leaves the channel's range: the range is kept by
// braking in time (the distance to each end always holds the stop from the present speed), so a
// target that jumps, a show switched mid-motion, a stop or a power-up never makes a step.
// Integer only (Q16 output units, per control tick), freestanding C++14.

#include <stdint.h>

#include "avar/device/config.hpp"

namespace avar {
namespace device {

/// A channel's limits in Q16 output units (output unit * 65536) and control ticks.
struct ChannelLimits {
  int64_t low, high;  ///< the range positions stay in, low <= high
  int64_t rest;       ///< where the channel starts at power-up and goes on stop, within the range
  int64_t speed;      ///< at most this much per tick, > 0
  int64_t accel;      ///< the speed changes by at most this much per tick, > 0
  /// stopping_distance(speed, accel): farther than this from an end (or from the target), the
  /// limiter needs no braking there, and skips computing it. Set by limiter_prepare.
  int64_t reach;
};

/// A channel's limits as stored (in flash, beside the shows): low, high, rest, speed, accel and
/// reach, each a little-endian 64-bit two's complement integer.
const uint8_t kLimitsSize = 48;
/// Reads stored limits (through AVAR_DEVICE_READ_BYTE: from program memory on AVR).
ChannelLimits read_limits(const uint8_t* stored);
/// Stores limits in kLimitsSize bytes at `out` (the host's exporter, a test's RAM copy).
void write_limits(const ChannelLimits& limits, uint8_t* out);

/// The distance a channel covers stopping from `speed` (first moving by it) decelerating by
/// `accel` per tick: speed + (speed - accel) + ... while positive.
int64_t stopping_distance(int64_t speed, int64_t accel);
/// Fills limits.reach from its speed and acceleration (player_init does it for every channel).
void limiter_prepare(ChannelLimits& limits);
/// Whether the limiter can use `limits`: low <= rest <= high, speed and acceleration above 0,
/// reach as limiter_prepare sets it (what a player checks of every stored channel).
bool limits_usable(const ChannelLimits& limits);

struct LimiterState {
  int64_t position;  ///< Q16 output units
  int64_t velocity;  ///< Q16 output units per tick
  int64_t target;    ///< the last tick's target (within the range)
  bool tracking;     ///< `target` is set: the target's own motion is followed
};

/// The state at rest (power-up): position `rest`, not moving.
LimiterState limiter_at_rest(const ChannelLimits& limits);

/// One tick toward `target` (Q16; clamped to the range first). A target that moves by at most the
/// speed per tick is followed with its own motion (a show within the limits is played exactly,
/// once caught up); a larger step of the target is a jump, approached as fast as the limits allow.
void limiter_step(const ChannelLimits& limits, LimiterState& state, int64_t target);

/// The largest speed (per tick) from which the channel stops within `distance` decelerating by
/// `accel` per tick, the first step moving by that speed: v + (v - a) + (v - 2a) + ... (its
/// positive terms) <= distance. 0 for a distance of 0 or less.
int64_t braking_speed(int64_t distance, int64_t accel);

/// The state's 16-bit output (its position rounded).
uint16_t limiter_output(const LimiterState& state);

}  // namespace device
}  // namespace avar
