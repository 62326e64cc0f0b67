#pragma once
// The motor behind every simulated CAN drive (ODrive axis, CiA 402 drive, MIT-style actuator): a
// rotor of fixed inertia driven by an impedance law, torque = kp·(p_goal − p) + kd·(v_goal − v)
// + torque_ff, saturated at the torque limit, its speed saturated at the velocity limit, and an
// encoder that reports the position quantised to its resolution. Units at the motor shaft:
// radians, rad/s, N·m, kg·m². Each drive converts from its protocol's units (turns, counts).
// Real-time safe: no allocation, no exception. Not thread-safe (one owner steps it).

namespace avar::sim {

struct CanMotorParams {
  double inertia = 1e-3;                   ///< rotor plus reflected load, kg·m² (> 0)
  double max_velocity = 60;                ///< rad/s (> 0)
  double max_torque = 2;                   ///< N·m (> 0)
  double viscous_friction = 1e-3;          ///< N·m per rad/s
  double encoder_counts_per_turn = 16384;  ///< resolution of the reported position (> 0)
};

/// What the drive's controller asks of the motor this instant.
struct MotorCommand {
  bool enabled = false;  ///< false: no torque, the rotor coasts to a stop on friction
  double position = 0;   ///< rad
  double velocity = 0;   ///< rad/s
  double kp = 0;         ///< N·m/rad
  double kd = 0;         ///< N·m·s/rad
  double torque_ff = 0;  ///< N·m
};

class CanMotorModel {
 public:
  /// Longest integration step; advance() splits longer spans (semi-implicit Euler).
  static constexpr double kMaxStep_s = 2.5e-4;

  CanMotorModel() = default;
  CanMotorModel(CanMotorParams params, double position) noexcept : params_(params), position_(position) {}

  /// Moves dt_s seconds forward under `command` (dt_s <= 0 does nothing).
  void advance(double dt_s, const MotorCommand& command) noexcept;

  /// Puts the rotor at `position` (rad), at rest.
  void set_position(double position) noexcept {
    position_ = position;
    velocity_ = 0;
  }
  /// A load torque opposing the motor (a test leaning on the arm), N·m.
  void set_external_torque(double torque) noexcept { external_torque_ = torque; }

  double position() const noexcept { return position_; }  ///< true position, rad
  /// What the encoder reports: the position quantised to the encoder's resolution, rad.
  double measured_position() const noexcept;
  double velocity() const noexcept { return velocity_; }  ///< rad/s
  double torque() const noexcept { return torque_; }      ///< last motor torque, N·m
  const CanMotorParams& params() const noexcept { return params_; }

  /// The critically damped kd for a stiffness kp on this rotor: 2·sqrt(kp·inertia).
  double critical_kd(double kp) const noexcept;

 private:
  CanMotorParams params_;
  double position_ = 0;
  double velocity_ = 0;
  double torque_ = 0;
  double external_torque_ = 0;
};

}  // namespace avar::sim
