#include "avar/sim/sim_maestro_usb.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/maestro_usb_codec.hpp"

namespace avar::sim {
namespace usb = firmware_iface::maestro_usb;
namespace {

constexpr std::uint8_t kScriptDone = 1;  // no script is loaded: it is "done"
// Offsets of scriptDone in the two variable layouts (Usc_protocol.cs: MicroMaestroVariables
// puts it after the stacks, MiniMaestroVariables after the program counter).
constexpr std::size_t kMicroScriptDoneOffset = 96;
constexpr std::size_t kMiniScriptDoneOffset = 6;

}  // namespace

SimMaestroUsb::SimMaestroUsb(SimMaestroConfig config, std::string serial)
    : config_(config), servos_(config_), serial_(std::move(serial)) {}

std::uint16_t SimMaestroUsb::product_id() const { return usb::product_id_for_channels(config_.channel_count); }

Status SimMaestroUsb::control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) {
  *transferred = 0;
  if (config_.log_limit > 0) {
    if (log_.size() == config_.log_limit) log_.pop_front();
    log_.push_back(setup);
  }
  Status s = Status::bad_data;
  if (setup.request_type == usb::kVendorOut) s = out_request(setup);
  else if (setup.request_type == usb::kVendorIn) s = in_request(setup, data, transferred);
  if (s != Status::ok) ++stalls_;
  return s;
}

Status SimMaestroUsb::out_request(const firmware_iface::UsbSetup& setup) {
  if (setup.length != 0) return Status::bad_data;
  const int channel = setup.index & 0x7F;
  switch (setup.request) {
    case usb::kSetTarget:
      if (setup.index >= config_.channel_count) return Status::bad_data;
      servos_.set_target(channel, setup.value);
      return Status::ok;
    case usb::kSetServoVariable:
      if (channel >= config_.channel_count || (setup.index & ~0xFF) != 0) return Status::bad_data;
      if (setup.index & usb::kAccelerationFlag) servos_.set_acceleration(channel, setup.value);
      else servos_.set_speed(channel, setup.value);
      return Status::ok;
    case usb::kClearErrors: servos_.clear_errors(); return Status::ok;
    default: return Status::bad_data;
  }
}

void SimMaestroUsb::write_records(std::span<std::uint8_t> reply, std::size_t at) const {
  for (int c = 0; c < config_.channel_count; ++c) {
    const usb::ServoStatus status{static_cast<std::uint16_t>(std::lround(servos_.output_pulse(c))), servos_.target(c),
                                  servos_.speed(c), static_cast<std::uint8_t>(servos_.acceleration(c))};
    usb::encode_servo_status(reply.subspan(at + static_cast<std::size_t>(c) * usb::kServoRecordSize), status);
  }
}

Status SimMaestroUsb::in_request(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) {
  const bool micro = config_.channel_count == 6;
  std::array<std::uint8_t, usb::kMaxReplySize> reply{};
  std::size_t size = 0;
  switch (setup.request) {
    case usb::kGetVariables:
      // Stack and call stack are empty, the program counter 0: no script runs.
      size = micro ? usb::kMicroVariablesSize + 6 * usb::kServoRecordSize : usb::kMiniVariablesSize;
      put_u16_le(&reply[usb::kErrorsOffset], servos_.errors());
      reply[micro ? kMicroScriptDoneOffset : kMiniScriptDoneOffset] = kScriptDone;
      if (micro) write_records(reply, usb::kMicroVariablesSize);
      break;
    case usb::kGetServoSettings:
      if (micro) return Status::bad_data;  // the Micro Maestro has no such request
      size = static_cast<std::size_t>(config_.channel_count) * usb::kServoRecordSize;
      write_records(reply, 0);
      break;
    default: return Status::bad_data;
  }
  const std::size_t n = std::min<std::size_t>(size, setup.length);
  std::copy_n(reply.begin(), n, data.begin());
  *transferred = n;
  return Status::ok;
}

}  // namespace avar::sim
