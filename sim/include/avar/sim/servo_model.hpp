#pragma once
// A hobby servo following its pulse width: first-order lag toward the commanded pulse, a top
// speed, and a deadband around the target. Positions are in pulse-width microseconds (the
// servo's own frame). Real-time safe.

namespace avar::sim {

struct ServoParams {
  double max_speed_us_per_s = 2400;  ///< ~60° in 0.12 s at ~11 µs/° (a standard analogue servo)
  double time_constant_s = 0.03;     ///< lag of the servo's position loop
  double deadband_us = 2;            ///< errors smaller than this do not move the horn
};

class ServoModel {
 public:
  ServoModel() = default;
  ServoModel(ServoParams params, double initial_position_us) : params_(params), position_(initial_position_us) {}

  /// Advances dt_s seconds toward pulse_us. pulse_us <= 0 means no pulses: an unpowered hobby
  /// servo stays where it is.
  void step(double dt_s, double pulse_us) noexcept;
  double position_us() const noexcept { return position_; }

 private:
  ServoParams params_;
  double position_ = 1500;
};

}  // namespace avar::sim
