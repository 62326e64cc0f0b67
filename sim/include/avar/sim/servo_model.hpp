#pragma once
// A hobby servo following its pulse width: a first-order lag toward the commanded pulse, capped
// by the motor's top speed, with a deadband around the target. Positions are in microseconds of
// pulse width (the servo's own frame: where the horn is, expressed as the pulse that would hold
// it there); times in seconds. Real-time safe: no allocation, no locks, no exceptions.
// Not thread-safe (one owner steps it).

namespace avar::sim {

/// How far a position loop with a first-order lag moves toward a goal `error` away in dt_s: the
/// exact response over dt for a constant goal, capped at max_speed * dt_s, 0 while |error| is
/// within the deadband; it never passes the goal (time_constant_s 0: only the cap). Units are
/// the caller's (µs of pulse, position steps). dt_s > 0, max_speed > 0.
double lag_step(double error, double dt_s, double time_constant_s, double max_speed, double deadband) noexcept;

struct ServoParams {
  /// Top speed of the horn in µs of pulse width per second. 2200 µs/s is a standard servo's
  /// 60° in 0.15 s (400°/s) where 1000 µs of pulse spans about 180° of travel (5.6 µs/°).
  double max_speed_us_per_s = 2200;
  /// Time constant of the servo's position loop, seconds (0 = no lag, only the top speed).
  double time_constant_s = 0.03;
  /// The horn does not move while |pulse - position| is at most this, µs.
  double deadband_us = 2;
};

class ServoModel {
 public:
  ServoModel() = default;
  /// params: max_speed_us_per_s > 0, time_constant_s >= 0, deadband_us >= 0 (the caller checks).
  ServoModel(ServoParams params, double initial_position_us) noexcept : params_(params), position_(initial_position_us) {}

  /// Advances dt_s seconds toward pulse_us. Over one step the position moves by
  /// (pulse - position) * (1 - exp(-dt / time_constant)), at most max_speed * dt, and not at all
  /// when the error is within the deadband; it never passes the pulse. pulse_us <= 0 means no
  /// pulses: an unpowered hobby servo stays where it is. dt_s <= 0 does nothing.
  void step(double dt_s, double pulse_us) noexcept;
  /// Where the horn is, µs of pulse width.
  double position_us() const noexcept { return position_; }
  const ServoParams& params() const noexcept { return params_; }

 private:
  ServoParams params_;
  double position_ = 1500;
};

}  // namespace avar::sim
