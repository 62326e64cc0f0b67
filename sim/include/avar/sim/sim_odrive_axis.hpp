#pragma once
// One simulated ODrive axis speaking CAN Simple (firmware 0.5.x; ../shared/protocols/odrive-cansimple.md)
// as one node of a simulated bus. It decodes what the real axis accepts (standard-id frames of
// its own node; anything else, malformed frames included, is ignored) and answers as it does:
//
// - state machine: IDLE <-> CLOSED_LOOP_CONTROL on Set Axis Requested State. Closed loop is
//   entered after `closed_loop_entry_s` when the axis is calibrated and has no error; otherwise,
//   and for any other requested state (the simulator runs no calibration sequence), the axis sets
//   INVALID_STATE (0x1) and stays IDLE. Estop sets ESTOP_REQUESTED (0x4000) and goes IDLE; any
//   axis error disarms (IDLE); Clear Errors clears them.
// - cyclic Heartbeat (0.5 or 0.6 layout) and, when configured, Encoder Estimates; Encoder
//   Estimates and Motor Error answer RTR requests.
// - the controller of firmware 0.5: position -> velocity -> torque cascade (pos_gain,
//   vel_gain), velocity clamped to the velocity limit, torque to current limit x torque constant;
//   input modes passthrough, pos_filter (2nd-order, input_filter_bandwidth) and trap_traj;
//   control modes position, velocity and torque.
// - a CanMotorModel turns the torque into motion (turns <-> radians at the shaft).
//
// Not thread-safe: its bus serialises every call.

#include <cstdint>
#include <deque>

#include "avar/firmware_iface/odrive_can_codec.hpp"
#include "avar/sim/can_motor_model.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::sim {

struct SimOdriveAxisConfig {
  std::uint8_t node = 0;  ///< 0..63
  firmware_iface::odrive::HeartbeatLayout heartbeat_layout = firmware_iface::odrive::HeartbeatLayout::v0_5;
  double heartbeat_period_s = 0.1;  ///< cyclic Heartbeat (the firmware's default 100 ms); 0: off
  double encoder_period_s = 0;      ///< cyclic Encoder Estimates (the firmware's default is 10 ms); 0: off
  double initial_position_turns = 0;
  CanMotorParams motor{};
  double torque_constant = 0.04;  ///< N·m per A (8.27 / KV)
  double pos_gain = 20;           ///< (turns/s) per turn (the firmware's default)
  double vel_gain = 0.5;          ///< N·m per turn/s (critically damps the default motor's inertia)
  double velocity_limit = 2;      ///< turns/s until Set Limits (the firmware's default)
  double current_limit = 10;      ///< A until Set Limits (the firmware's default)
  /// The pos_filter's bandwidth, used as the firmware does (rad/s: kp = bw², ki = 2·bw).
  double input_filter_bandwidth = 2;
  double trap_vel_limit = 2;       ///< turns/s
  double trap_accel_limit = 0.5;   ///< turns/s²
  double trap_decel_limit = 0.5;   ///< turns/s²
  double closed_loop_entry_s = 0;  ///< from the request to CLOSED_LOOP_CONTROL
  bool calibrated = true;          ///< false: closed loop is refused with INVALID_STATE
  /// Firmware 0.5 sets input_pos to the present position on entering closed loop; false makes
  /// the axis keep whatever input_pos it was sent (or 0), to test that a host avoids a jump itself.
  bool hold_position_on_entry = true;
};

class SimOdriveAxis final : public CanNode {
 public:
  explicit SimOdriveAxis(SimOdriveAxisConfig config);

  void receive(const firmware_iface::CanFrame& frame) override;
  bool peek_transmit(firmware_iface::CanFrame* frame) const override;
  void pop_transmit() override;
  void advance(double dt_s) override;

  // Ground truth and what the host set, for tests.
  double position_turns() const noexcept;  ///< the rotor's true position
  double velocity_turns_per_s() const noexcept;
  std::uint8_t state() const noexcept { return state_; }
  std::uint32_t axis_error() const noexcept { return axis_error_; }
  std::int32_t control_mode() const noexcept { return control_mode_; }
  std::int32_t input_mode() const noexcept { return input_mode_; }
  double input_pos() const noexcept { return input_pos_; }  ///< turns
  double velocity_limit() const noexcept { return velocity_limit_; }
  double current_limit() const noexcept { return current_limit_; }
  std::uint64_t heartbeats_sent() const noexcept { return heartbeats_sent_; }
  std::uint64_t frames_received() const noexcept { return frames_received_; }  ///< this node's frames it accepted
  CanMotorModel& motor() noexcept { return motor_; }

  // Fault injection.
  /// Latches axis error bits (the axis disarms: IDLE), as the firmware does on a fault.
  void inject_axis_error(std::uint32_t bits, std::uint64_t motor_error = 0);
  /// Stops (false) or resumes the cyclic heartbeat; RTR answers go on.
  void set_heartbeat_enabled(bool on) noexcept { heartbeat_enabled_ = on; }
  /// Stops answering RTR requests (a firmware with the feature off, or a lost reply).
  void set_answers_requests(bool on) noexcept { answers_requests_ = on; }
  void set_calibrated(bool on) noexcept { config_.calibrated = on; }
  /// Moves the rotor (a hand turning the shaft while idle), turns.
  void set_position_turns(double turns) noexcept;

 private:
  void request_state(std::uint32_t state);
  void enter_idle() noexcept;
  void enter_closed_loop() noexcept;
  void queue(const firmware_iface::CanFrame& frame);
  void send_heartbeat();
  void send_encoder_estimates();
  /// One controller step of h seconds: updates the setpoints from the input mode and returns the
  /// motor torque (N·m) to apply.
  double control_step(double h) noexcept;
  void update_setpoints(double h) noexcept;

  SimOdriveAxisConfig config_;
  CanMotorModel motor_;
  std::deque<firmware_iface::CanFrame> tx_;

  std::uint8_t state_ = static_cast<std::uint8_t>(firmware_iface::odrive::AxisState::idle);
  std::uint32_t axis_error_ = 0;
  std::uint64_t motor_error_ = 0;
  bool entering_closed_loop_ = false;
  double entry_elapsed_s_ = 0;

  std::int32_t control_mode_ = static_cast<std::int32_t>(firmware_iface::odrive::ControlMode::position);
  std::int32_t input_mode_ = static_cast<std::int32_t>(firmware_iface::odrive::InputMode::passthrough);
  double velocity_limit_;
  double current_limit_;
  // Inputs (turns, turns/s, N·m) and the controller's setpoints derived from them.
  double input_pos_ = 0, input_vel_ = 0, input_torque_ = 0;
  double pos_setpoint_ = 0, vel_setpoint_ = 0, torque_setpoint_ = 0;
  bool trajectory_done_ = true;

  bool heartbeat_enabled_ = true;
  bool answers_requests_ = true;
  double heartbeat_elapsed_s_ = 0;
  double encoder_elapsed_s_ = 0;
  std::uint64_t heartbeats_sent_ = 0;
  std::uint64_t frames_received_ = 0;
};

}  // namespace avar::sim
