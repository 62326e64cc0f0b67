#pragma once
// ODrive "CAN Simple" (firmware 0.5.x; ../shared/protocols/odrive-cansimple.md): pure encoders and
// decoders of the messages avar uses. No I/O, no clock, no allocation, no exception: every
// function but the describe_* ones is real-time safe.
//
// Each axis is one node (0..63) on 11-bit identifiers: id = node << 5 | command. Payloads are
// little-endian; floats are IEEE-754 single precision. Units (firmware 0.5+): positions in turns,
// velocities in turns/s, torques in N·m, currents in A. Encoders take node < 64 (precondition:
// higher bits are dropped). Decoders check the command, the frame kind (data, standard id) and
// the length, and return false for anything else; they do not check the node (the caller routes
// by odrive_node()).

#include <cstdint>
#include <string>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface::odrive {

inline constexpr std::uint8_t kMaxNode = 63;

enum Command : std::uint8_t {
  kHeartbeat = 0x01,
  kEstop = 0x02,
  kGetMotorError = 0x03,
  kGetEncoderError = 0x04,
  kSetAxisRequestedState = 0x07,
  kGetEncoderEstimates = 0x09,
  kSetControllerModes = 0x0B,
  kSetInputPos = 0x0C,
  kSetInputVel = 0x0D,
  kSetInputTorque = 0x0E,
  kSetLimits = 0x0F,
  kClearErrors = 0x18,
};

enum class AxisState : std::uint8_t {
  undefined = 0,
  idle = 1,
  startup_sequence = 2,
  full_calibration_sequence = 3,
  motor_calibration = 4,
  sensorless_control = 5,
  encoder_index_search = 6,
  encoder_offset_calibration = 7,
  closed_loop_control = 8,
  lockin_spin = 9,
  encoder_dir_find = 10,
  homing = 11,
  encoder_hall_polarity_calibration = 12,
  encoder_hall_phase_calibration = 13,
};

enum class ControlMode : std::int32_t { voltage = 0, torque = 1, velocity = 2, position = 3 };

enum class InputMode : std::int32_t {
  inactive = 0,
  passthrough = 1,
  vel_ramp = 2,
  pos_filter = 3,
  mix_channels = 4,
  trap_traj = 5,
  torque_ramp = 6,
  mirror = 7,
};

/// Axis error bits of firmware 0.5.x (Heartbeat bytes 0..3).
enum AxisError : std::uint32_t {
  kInvalidState = 0x1,
  kDcBusUnderVoltage = 0x2,
  kDcBusOverVoltage = 0x4,
  kCurrentMeasurementTimeout = 0x8,
  kBrakeResistorDisarmed = 0x10,
  kMotorDisarmed = 0x20,
  kMotorFailed = 0x40,
  kSensorlessEstimatorFailed = 0x80,
  kEncoderFailed = 0x100,
  kControllerFailed = 0x200,
  kPosCtrlDuringSensorless = 0x400,
  kWatchdogTimerExpired = 0x800,
  kMinEndstopPressed = 0x1000,
  kMaxEndstopPressed = 0x2000,
  kEstopRequested = 0x4000,
  kDcBusUnderCurrent = 0x8000,
  kDcBusOverCurrent = 0x10000,
  kHomingWithoutEndstop = 0x20000,
};

/// Which firmware's heartbeat layout a node sends.
enum class HeartbeatLayout {
  v0_5,  ///< u32 axis error, u8 state, u8 motor-error flag, u8 encoder-error flag, u8 controller-error (bit 0) | trajectory-done
         ///< (bit 7)
  v0_6,  ///< u32 axis error, u8 state, u8 procedure result, u8 trajectory-done flag, u8 reserved (unconfirmed, from a third-party
         ///< crate)
};

constexpr std::uint32_t can_id(std::uint8_t node, std::uint8_t command) noexcept {
  return static_cast<std::uint32_t>(node & kMaxNode) << 5 | (command & 0x1Fu);
}
constexpr std::uint8_t odrive_node(std::uint32_t id) noexcept { return static_cast<std::uint8_t>((id >> 5) & kMaxNode); }
constexpr std::uint8_t odrive_command(std::uint32_t id) noexcept { return static_cast<std::uint8_t>(id & 0x1F); }

struct Heartbeat {
  std::uint32_t axis_error = 0;   ///< AxisError bits
  std::uint8_t state = 0;         ///< AxisState value (kept raw: a device may report one we do not know)
  bool motor_error = false;       ///< 0.5 only
  bool encoder_error = false;     ///< 0.5 only
  bool controller_error = false;  ///< 0.5 only
  bool trajectory_done = false;
  std::uint8_t procedure_result = 0;  ///< 0.6 only
  bool in_state(AxisState s) const noexcept { return state == static_cast<std::uint8_t>(s); }
};

struct EncoderEstimates {
  float position = 0;  ///< turns
  float velocity = 0;  ///< turns/s
};

/// Set Input Pos as the device reads it.
struct InputPos {
  float position = 0;    ///< turns
  double vel_ff = 0;     ///< turns/s, 0.001 resolution
  double torque_ff = 0;  ///< N·m, 0.001 resolution
};

struct ControllerModes {
  std::int32_t control_mode = 0;  ///< ControlMode value (raw)
  std::int32_t input_mode = 0;    ///< InputMode value (raw)
};

struct Limits {
  float velocity_limit = 0;  ///< turns/s
  float current_limit = 0;   ///< A
};

// Host -> axis.
CanFrame encode_estop(std::uint8_t node) noexcept;
CanFrame encode_clear_errors(std::uint8_t node) noexcept;
CanFrame encode_set_axis_state(std::uint8_t node, AxisState state) noexcept;
CanFrame encode_set_controller_modes(std::uint8_t node, ControlMode control, InputMode input) noexcept;
/// vel_ff and torque_ff are sent as i16 × 0.001: rounded to the nearest step, saturated at
/// ±32.767; a non-finite feed-forward is sent as 0.
CanFrame encode_set_input_pos(std::uint8_t node, float position, double vel_ff = 0, double torque_ff = 0) noexcept;
CanFrame encode_set_input_vel(std::uint8_t node, float velocity, float torque_ff = 0) noexcept;
CanFrame encode_set_input_torque(std::uint8_t node, float torque) noexcept;
CanFrame encode_set_limits(std::uint8_t node, float velocity_limit, float current_limit) noexcept;
/// RTR requests (DLC 8, the length of the answer).
CanFrame encode_get_encoder_estimates(std::uint8_t node) noexcept;
CanFrame encode_get_motor_error(std::uint8_t node) noexcept;

// Axis -> host.
CanFrame encode_heartbeat(std::uint8_t node, const Heartbeat& heartbeat, HeartbeatLayout layout = HeartbeatLayout::v0_5) noexcept;
CanFrame encode_encoder_estimates(std::uint8_t node, float position, float velocity) noexcept;
CanFrame encode_motor_error(std::uint8_t node, std::uint64_t motor_error) noexcept;

bool decode_heartbeat(const CanFrame& frame, HeartbeatLayout layout, Heartbeat* out) noexcept;
bool decode_encoder_estimates(const CanFrame& frame, EncoderEstimates* out) noexcept;
bool decode_motor_error(const CanFrame& frame, std::uint64_t* out) noexcept;

// What an axis reads from the host's frames (the simulator's side).
bool decode_set_axis_state(const CanFrame& frame, std::uint32_t* state) noexcept;
bool decode_set_controller_modes(const CanFrame& frame, ControllerModes* out) noexcept;
bool decode_set_input_pos(const CanFrame& frame, InputPos* out) noexcept;
/// out: velocity (turns/s), torque_ff (N·m).
bool decode_set_input_vel(const CanFrame& frame, float* velocity, float* torque_ff) noexcept;
bool decode_set_input_torque(const CanFrame& frame, float* torque) noexcept;
bool decode_set_limits(const CanFrame& frame, Limits* out) noexcept;
/// A data frame of `command` with no payload requirement (Estop, Clear Errors).
bool is_command(const CanFrame& frame, Command command) noexcept;
/// An RTR request of `command`.
bool is_request(const CanFrame& frame, Command command) noexcept;

/// "CLOSED_LOOP_CONTROL", "IDLE"...; "UNKNOWN" for values outside the table.
const char* axis_state_name(std::uint8_t state) noexcept;
/// The name of one 0.5.x axis error bit ("motor failed"), or nullptr for an unknown bit.
const char* axis_error_name(std::uint32_t bit) noexcept;
/// The DeviceFault bits (actuator_link.hpp) an axis error stands for: voltage, electrical,
/// encoder, or other. Does not include kDeviceFaultState (the driver decides that).
std::uint32_t axis_error_faults(std::uint32_t axis_error) noexcept;

/// For messages (allocates): "motor failed, encoder failed", unknown bits as "0x40000",
/// "none" for 0.
std::string describe_axis_error(std::uint32_t axis_error);
/// "IDLE", or "state 42" for an unknown value.
std::string describe_axis_state(std::uint8_t state);

}  // namespace avar::firmware_iface::odrive
