#include "avar/firmware_iface/odrive_can_codec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::firmware_iface::odrive {
namespace {

/// round(value / 0.001), saturated to i16; non-finite values are 0.
std::int16_t milli_i16(double value) noexcept {
  if (!std::isfinite(value)) return 0;
  return static_cast<std::int16_t>(std::clamp(std::round(value * 1000.0), -32768.0, 32767.0));
}

CanFrame data(std::uint8_t node, Command command, std::uint8_t dlc) noexcept {
  CanFrame f;
  f.id = can_id(node, command);
  f.dlc = dlc;
  return f;
}

CanFrame two_f32(std::uint8_t node, Command command, float a, float b) noexcept {
  CanFrame f = data(node, command, 8);
  put_f32_le(&f.data[0], a);
  put_f32_le(&f.data[4], b);
  return f;
}

/// A standard-id data frame of `command` with at least `min_dlc` bytes.
bool is_data(const CanFrame& f, Command command, std::uint8_t min_dlc) noexcept {
  return !f.error && !f.extended && !f.rtr && f.id <= kCanMaxStandardId && odrive_command(f.id) == command && f.dlc >= min_dlc &&
         f.dlc <= kCanMaxData;
}

constexpr std::pair<std::uint32_t, const char*> kAxisErrorNames[] = {
    {kInvalidState, "invalid state"},
    {kDcBusUnderVoltage, "DC bus under-voltage"},
    {kDcBusOverVoltage, "DC bus over-voltage"},
    {kCurrentMeasurementTimeout, "current measurement timeout"},
    {kBrakeResistorDisarmed, "brake resistor disarmed"},
    {kMotorDisarmed, "motor disarmed"},
    {kMotorFailed, "motor failed"},
    {kSensorlessEstimatorFailed, "sensorless estimator failed"},
    {kEncoderFailed, "encoder failed"},
    {kControllerFailed, "controller failed"},
    {kPosCtrlDuringSensorless, "position control during sensorless"},
    {kWatchdogTimerExpired, "watchdog timer expired"},
    {kMinEndstopPressed, "min endstop pressed"},
    {kMaxEndstopPressed, "max endstop pressed"},
    {kEstopRequested, "estop requested"},
    {kDcBusUnderCurrent, "DC bus under-current"},
    {kDcBusOverCurrent, "DC bus over-current"},
    {kHomingWithoutEndstop, "homing without endstop"},
};

constexpr const char* kStateNames[] = {
    "UNDEFINED",
    "IDLE",
    "STARTUP_SEQUENCE",
    "FULL_CALIBRATION_SEQUENCE",
    "MOTOR_CALIBRATION",
    "SENSORLESS_CONTROL",
    "ENCODER_INDEX_SEARCH",
    "ENCODER_OFFSET_CALIBRATION",
    "CLOSED_LOOP_CONTROL",
    "LOCKIN_SPIN",
    "ENCODER_DIR_FIND",
    "HOMING",
    "ENCODER_HALL_POLARITY_CALIBRATION",
    "ENCODER_HALL_PHASE_CALIBRATION",
};

}  // namespace

CanFrame encode_estop(std::uint8_t node) noexcept { return data(node, kEstop, 0); }
CanFrame encode_clear_errors(std::uint8_t node) noexcept { return data(node, kClearErrors, 0); }

CanFrame encode_set_axis_state(std::uint8_t node, AxisState state) noexcept {
  CanFrame f = data(node, kSetAxisRequestedState, 4);
  put_u32_le(&f.data[0], static_cast<std::uint32_t>(state));
  return f;
}

CanFrame encode_set_controller_modes(std::uint8_t node, ControlMode control, InputMode input) noexcept {
  CanFrame f = data(node, kSetControllerModes, 8);
  put_u32_le(&f.data[0], static_cast<std::uint32_t>(control));
  put_u32_le(&f.data[4], static_cast<std::uint32_t>(input));
  return f;
}

CanFrame encode_set_input_pos(std::uint8_t node, float position, double vel_ff, double torque_ff) noexcept {
  CanFrame f = data(node, kSetInputPos, 8);
  put_f32_le(&f.data[0], position);
  put_i16_le(&f.data[4], milli_i16(vel_ff));
  put_i16_le(&f.data[6], milli_i16(torque_ff));
  return f;
}

CanFrame encode_set_input_vel(std::uint8_t node, float velocity, float torque_ff) noexcept {
  return two_f32(node, kSetInputVel, velocity, torque_ff);
}

CanFrame encode_set_input_torque(std::uint8_t node, float torque) noexcept {
  CanFrame f = data(node, kSetInputTorque, 4);
  put_f32_le(&f.data[0], torque);
  return f;
}

CanFrame encode_set_limits(std::uint8_t node, float velocity_limit, float current_limit) noexcept {
  return two_f32(node, kSetLimits, velocity_limit, current_limit);
}

CanFrame encode_get_encoder_estimates(std::uint8_t node) noexcept {
  return can_remote_frame(can_id(node, kGetEncoderEstimates), 8);
}
CanFrame encode_get_motor_error(std::uint8_t node) noexcept { return can_remote_frame(can_id(node, kGetMotorError), 8); }

CanFrame encode_heartbeat(std::uint8_t node, const Heartbeat& h, HeartbeatLayout layout) noexcept {
  CanFrame f = data(node, kHeartbeat, 8);
  put_u32_le(&f.data[0], h.axis_error);
  f.data[4] = h.state;
  if (layout == HeartbeatLayout::v0_5) {
    f.data[5] = h.motor_error ? 1 : 0;
    f.data[6] = h.encoder_error ? 1 : 0;
    f.data[7] = static_cast<std::uint8_t>((h.controller_error ? 0x01 : 0) | (h.trajectory_done ? 0x80 : 0));
  } else {
    f.data[5] = h.procedure_result;
    f.data[6] = h.trajectory_done ? 1 : 0;
  }
  return f;
}

CanFrame encode_encoder_estimates(std::uint8_t node, float position, float velocity) noexcept {
  return two_f32(node, kGetEncoderEstimates, position, velocity);
}

CanFrame encode_motor_error(std::uint8_t node, std::uint64_t motor_error) noexcept {
  CanFrame f = data(node, kGetMotorError, 8);
  put_u32_le(&f.data[0], static_cast<std::uint32_t>(motor_error));
  put_u32_le(&f.data[4], static_cast<std::uint32_t>(motor_error >> 32));
  return f;
}

bool decode_heartbeat(const CanFrame& f, HeartbeatLayout layout, Heartbeat* out) noexcept {
  if (!is_data(f, kHeartbeat, 8)) return false;
  Heartbeat h;
  h.axis_error = get_u32_le(&f.data[0]);
  h.state = f.data[4];
  if (layout == HeartbeatLayout::v0_5) {
    h.motor_error = f.data[5] & 0x01;
    h.encoder_error = f.data[6] & 0x01;
    h.controller_error = f.data[7] & 0x01;
    h.trajectory_done = f.data[7] & 0x80;
  } else {
    h.procedure_result = f.data[5];
    h.trajectory_done = f.data[6] != 0;
  }
  *out = h;
  return true;
}

bool decode_encoder_estimates(const CanFrame& f, EncoderEstimates* out) noexcept {
  if (!is_data(f, kGetEncoderEstimates, 8)) return false;
  out->position = get_f32_le(&f.data[0]);
  out->velocity = get_f32_le(&f.data[4]);
  return true;
}

bool decode_motor_error(const CanFrame& f, std::uint64_t* out) noexcept {
  if (!is_data(f, kGetMotorError, 8)) return false;
  *out = static_cast<std::uint64_t>(get_u32_le(&f.data[0])) | static_cast<std::uint64_t>(get_u32_le(&f.data[4])) << 32;
  return true;
}

bool decode_set_axis_state(const CanFrame& f, std::uint32_t* state) noexcept {
  if (!is_data(f, kSetAxisRequestedState, 4)) return false;
  *state = get_u32_le(&f.data[0]);
  return true;
}

bool decode_set_controller_modes(const CanFrame& f, ControllerModes* out) noexcept {
  if (!is_data(f, kSetControllerModes, 8)) return false;
  out->control_mode = static_cast<std::int32_t>(get_u32_le(&f.data[0]));
  out->input_mode = static_cast<std::int32_t>(get_u32_le(&f.data[4]));
  return true;
}

bool decode_set_input_pos(const CanFrame& f, InputPos* out) noexcept {
  if (!is_data(f, kSetInputPos, 8)) return false;
  out->position = get_f32_le(&f.data[0]);
  out->vel_ff = get_i16_le(&f.data[4]) * 0.001;
  out->torque_ff = get_i16_le(&f.data[6]) * 0.001;
  return true;
}

bool decode_set_input_vel(const CanFrame& f, float* velocity, float* torque_ff) noexcept {
  if (!is_data(f, kSetInputVel, 8)) return false;
  *velocity = get_f32_le(&f.data[0]);
  *torque_ff = get_f32_le(&f.data[4]);
  return true;
}

bool decode_set_input_torque(const CanFrame& f, float* torque) noexcept {
  if (!is_data(f, kSetInputTorque, 4)) return false;
  *torque = get_f32_le(&f.data[0]);
  return true;
}

bool decode_set_limits(const CanFrame& f, Limits* out) noexcept {
  if (!is_data(f, kSetLimits, 8)) return false;
  out->velocity_limit = get_f32_le(&f.data[0]);
  out->current_limit = get_f32_le(&f.data[4]);
  return true;
}

bool is_command(const CanFrame& f, Command command) noexcept { return is_data(f, command, 0); }

bool is_request(const CanFrame& f, Command command) noexcept {
  return !f.error && !f.extended && f.rtr && f.id <= kCanMaxStandardId && odrive_command(f.id) == command;
}

const char* axis_state_name(std::uint8_t state) noexcept {
  return state < std::size(kStateNames) ? kStateNames[state] : "UNKNOWN";
}

const char* axis_error_name(std::uint32_t bit) noexcept {
  for (const auto& [b, name] : kAxisErrorNames)
    if (b == bit) return name;
  return nullptr;
}

std::uint32_t axis_error_faults(std::uint32_t axis_error) noexcept {
  std::uint32_t faults = 0;
  if (axis_error & (kDcBusUnderVoltage | kDcBusOverVoltage)) faults |= kDeviceVoltage;
  if (axis_error & (kCurrentMeasurementTimeout | kBrakeResistorDisarmed | kMotorDisarmed | kMotorFailed | kDcBusUnderCurrent |
                    kDcBusOverCurrent))
    faults |= kDeviceElectrical;
  if (axis_error & (kSensorlessEstimatorFailed | kEncoderFailed)) faults |= kDeviceEncoder;
  if (axis_error & (kInvalidState | kControllerFailed | kPosCtrlDuringSensorless | kWatchdogTimerExpired | kMinEndstopPressed |
                    kMaxEndstopPressed | kEstopRequested | kHomingWithoutEndstop | ~0x3FFFFu))
    faults |= kDeviceOther;
  return faults;
}

std::string describe_axis_error(std::uint32_t axis_error) {
  if (axis_error == 0) return "none";
  std::string out;
  for (int bit = 0; bit < 32; ++bit) {
    const std::uint32_t b = 1u << bit;
    if (!(axis_error & b)) continue;
    if (!out.empty()) out += ", ";
    if (const char* name = axis_error_name(b)) {
      out += name;
    } else {
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%X", b);
      out += hex;
    }
  }
  return out;
}

std::string describe_axis_state(std::uint8_t state) {
  if (state < std::size(kStateNames)) return kStateNames[state];
  return "state " + std::to_string(state);
}

}  // namespace avar::firmware_iface::odrive
