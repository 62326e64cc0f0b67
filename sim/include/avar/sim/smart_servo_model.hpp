#pragma once
// A smart servo's motor and body, shared by every simulated smart-servo bus (DYNAMIXEL,
// Feetech): a position loop with a first-order lag toward the goal (lag_step), a speed cap, an
// acceleration cap, a load that rises with acceleration, speed and an external load, and a
// temperature that rises with load and falls toward ambient. Positions in the device's own steps,
// speeds in steps/s, time in seconds, temperatures in °C. The protocol's registers (goal,
// profile or goal speed, protection) stay with each simulated device.
// Real-time safe: no allocation, no exception. Not thread-safe (one owner steps it).

namespace avar::sim {

struct SmartServoParams {
  double max_speed = 3000;           ///< no-load top speed, steps/s (> 0)
  double max_acceleration = 60'000;  ///< the motor's own limit, steps/s² (> 0)
  double time_constant_s = 0.02;     ///< of the position loop (>= 0)
  double deadband = 0;               ///< steps the horn does not move for
  double ambient_c = 25;
  double heating_c_per_s_at_full_load = 2;  ///< temperature rise rate at 100 % load
  double cooling_per_s = 0.01;              ///< fraction of the excess over ambient lost per second
};

/// Load at full acceleration and at full speed (fractions of rated torque).
inline constexpr double kLoadAtMaxAcceleration = 0.3;
inline constexpr double kLoadAtMaxSpeed = 0.2;

class SmartServoModel {
 public:
  /// Longest single step; advance() splits longer spans.
  static constexpr double kMaxStep_s = 0.001;

  SmartServoModel() = default;
  SmartServoModel(SmartServoParams params, double position) noexcept
      : params_(params), position_(position), temperature_(params.ambient_c) {}

  /// Moves dt_s seconds forward (dt_s <= 0 does nothing). With torque on, the horn follows
  /// `goal` at most min(speed_limit, max_speed) fast (speed_limit <= 0: max_speed) and changes
  /// speed at most min(acceleration_limit, max_acceleration) per second (acceleration_limit <= 0:
  /// max_acceleration); its load is external + 0.3 acceleration/max_acceleration + 0.2
  /// speed/max_speed, within -1..1. With torque off it stops at once and carries no load.
  /// Either way the temperature rises at heating * |load| and cools toward ambient.
  void advance(double dt_s, bool torque, double goal, double speed_limit = 0, double acceleration_limit = 0) noexcept;

  /// Puts the horn at `position`, at rest (a servo told where its centre is).
  void set_position(double position) noexcept {
    position_ = position;
    velocity_ = 0;
  }
  /// The load the horn holds (a test pressing on the arm), signed fraction of rated torque.
  void set_external_load(double load) noexcept { external_load_ = load; }
  void set_temperature_c(double celsius) noexcept { temperature_ = celsius; }

  double position() const noexcept { return position_; }
  double velocity() const noexcept { return velocity_; }  ///< steps/s
  double load() const noexcept { return load_; }          ///< signed fraction of rated torque
  double temperature_c() const noexcept { return temperature_; }
  const SmartServoParams& params() const noexcept { return params_; }

 private:
  void step(double dt_s, bool torque, double goal, double speed_limit, double acceleration_limit) noexcept;

  SmartServoParams params_;
  double position_ = 0;
  double velocity_ = 0;
  double load_ = 0;
  double external_load_ = 0;
  double temperature_ = 25;
};

}  // namespace avar::sim
