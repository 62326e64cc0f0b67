#include "avar/firmware_iface/cia402_codec.hpp"

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/canopen_codec.hpp"

namespace avar::firmware_iface::cia402 {
namespace {

struct Cia402StateRow {
  State state;
  std::uint16_t mask;
  std::uint16_t value;
};
// Section 6's table (no statusword matches two rows).
constexpr Cia402StateRow kCia402States[] = {
    {State::not_ready_to_switch_on, 0x4F, 0x00}, {State::switch_on_disabled, 0x4F, 0x40},
    {State::ready_to_switch_on, 0x6F, 0x21},     {State::switched_on, 0x6F, 0x23},
    {State::operation_enabled, 0x6F, 0x27},      {State::quick_stop_active, 0x6F, 0x07},
    {State::fault_reaction_active, 0x4F, 0x0F},  {State::fault, 0x4F, 0x08},
};

bool cia402_pdo_frame(const CanFrame& f, std::uint32_t cob_id) noexcept {
  return f.id == cob_id && !f.extended && !f.rtr && !f.error && f.dlc >= 6;
}

CanFrame cia402_word_and_i32(std::uint32_t cob_id, std::uint16_t word, std::int32_t value) noexcept {
  CanFrame f;
  f.id = cob_id;
  f.dlc = 6;
  put_u16_le(&f.data[0], word);
  put_i32_le(&f.data[2], value);
  return f;
}

void cia402_read_word_and_i32(const CanFrame& f, std::uint16_t* word, std::int32_t* value) noexcept {
  *word = get_u16_le(&f.data[0]);
  *value = get_i32_le(&f.data[2]);
}

}  // namespace

const char* mode_name(std::int8_t mode) noexcept {
  switch (static_cast<Mode>(mode)) {
    case Mode::none: return "no mode";
    case Mode::profile_position: return "profile position";
    case Mode::velocity: return "velocity";
    case Mode::profile_velocity: return "profile velocity";
    case Mode::profile_torque: return "profile torque";
    case Mode::homing: return "homing";
    case Mode::interpolated_position: return "interpolated position";
    case Mode::cyclic_synchronous_position: return "cyclic synchronous position";
    case Mode::cyclic_synchronous_velocity: return "cyclic synchronous velocity";
    case Mode::cyclic_synchronous_torque: return "cyclic synchronous torque";
  }
  return mode < 0 ? "vendor mode" : "unknown mode";
}

std::uint32_t supported_mode_bit(std::int8_t mode) noexcept {
  // Bits of 0x6502: 0 PP, 1 vl, 2 PV, 3 PT, 5 homing, 6 IP, 7 CSP, 8 CSV, 9 CST.
  switch (static_cast<Mode>(mode)) {
    case Mode::profile_position: return 1u << 0;
    case Mode::velocity: return 1u << 1;
    case Mode::profile_velocity: return 1u << 2;
    case Mode::profile_torque: return 1u << 3;
    case Mode::homing: return 1u << 5;
    case Mode::interpolated_position: return 1u << 6;
    case Mode::cyclic_synchronous_position: return 1u << 7;
    case Mode::cyclic_synchronous_velocity: return 1u << 8;
    case Mode::cyclic_synchronous_torque: return 1u << 9;
    case Mode::none: break;
  }
  return 0;
}

State decode_state(std::uint16_t statusword) noexcept {
  for (const Cia402StateRow& row : kCia402States)
    if ((statusword & row.mask) == row.value) return row.state;
  return State::unknown;
}

std::uint16_t state_bits(State state) noexcept {
  for (const Cia402StateRow& row : kCia402States)
    if (row.state == state) return row.value;
  return 0;
}

const char* state_name(State state) noexcept {
  switch (state) {
    case State::not_ready_to_switch_on: return "Not ready to switch on";
    case State::switch_on_disabled: return "Switch on disabled";
    case State::ready_to_switch_on: return "Ready to switch on";
    case State::switched_on: return "Switched on";
    case State::operation_enabled: return "Operation enabled";
    case State::quick_stop_active: return "Quick stop active";
    case State::fault_reaction_active: return "Fault reaction active";
    case State::fault: return "Fault";
    case State::unknown: break;
  }
  return "unknown state";
}

Transition next_state(State state, std::uint16_t controlword, std::uint16_t previous_controlword) noexcept {
  switch (state) {
    case State::fault:
      if ((controlword & kCwFaultReset) && !(previous_controlword & kCwFaultReset)) return {State::switch_on_disabled, 15};
      break;
    case State::switch_on_disabled:
      if (is_shutdown(controlword)) return {State::ready_to_switch_on, 2};
      break;
    case State::ready_to_switch_on:
      if (is_disable_voltage(controlword) || is_quick_stop(controlword)) return {State::switch_on_disabled, 7};
      if (is_switch_on(controlword)) return {State::switched_on, 3};
      break;
    case State::switched_on:
      if (is_disable_voltage(controlword) || is_quick_stop(controlword)) return {State::switch_on_disabled, 10};
      if (is_shutdown(controlword)) return {State::ready_to_switch_on, 6};
      if (is_enable_operation(controlword)) return {State::operation_enabled, 4};
      break;
    case State::operation_enabled:
      if (is_disable_voltage(controlword)) return {State::switch_on_disabled, 9};
      if (is_quick_stop(controlword)) return {State::quick_stop_active, 11};
      if (is_shutdown(controlword)) return {State::ready_to_switch_on, 8};
      if (is_disable_operation(controlword)) return {State::switched_on, 5};
      break;
    case State::quick_stop_active:
      if (is_disable_voltage(controlword)) return {State::switch_on_disabled, 12};
      if (is_enable_operation(controlword)) return {State::operation_enabled, 16};
      break;
    case State::not_ready_to_switch_on:
    case State::fault_reaction_active:
    case State::unknown: break;
  }
  return {state, 0};
}

std::uint32_t emcy_device_faults(std::uint16_t code) noexcept {
  if (code == 0) return 0;
  if (code == 0x7121 || code == 0x8311) return kDeviceOverload;  // motor blocked, excess torque
  if ((code & 0xFF00) == 0x7300) return kDeviceEncoder;
  switch (code >> 12) {
    case 0x2: return kDeviceElectrical;
    case 0x3: return kDeviceVoltage;
    case 0x4: return kDeviceOverheat;
    default: return kDeviceOther;
  }
}

CanFrame encode_control_target(std::uint32_t cob_id, std::uint16_t controlword, std::int32_t target) noexcept {
  return cia402_word_and_i32(cob_id, controlword, target);
}

bool decode_control_target(const CanFrame& f, std::uint32_t cob_id, std::uint16_t* controlword, std::int32_t* target) noexcept {
  if (!cia402_pdo_frame(f, cob_id)) return false;
  cia402_read_word_and_i32(f, controlword, target);
  return true;
}

CanFrame encode_status_position(std::uint32_t cob_id, std::uint16_t statusword, std::int32_t position) noexcept {
  return cia402_word_and_i32(cob_id, statusword, position);
}

bool decode_status_position(const CanFrame& f, std::uint32_t cob_id, std::uint16_t* statusword, std::int32_t* position) noexcept {
  if (!cia402_pdo_frame(f, cob_id)) return false;
  cia402_read_word_and_i32(f, statusword, position);
  return true;
}

}  // namespace avar::firmware_iface::cia402
