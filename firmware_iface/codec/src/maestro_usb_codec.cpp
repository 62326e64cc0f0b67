#include "avar/firmware_iface/maestro_usb_codec.hpp"

#include <algorithm>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::firmware_iface::maestro_usb {
namespace {

constexpr bool is_micro(int channel_count) { return channel_count == 6; }

std::size_t records_offset(int channel_count) { return is_micro(channel_count) ? kMicroVariablesSize : 0; }

}  // namespace

std::uint16_t product_id_for_channels(int channel_count) noexcept {
  switch (channel_count) {
    case 6: return kProductIds[0];
    case 12: return kProductIds[1];
    case 18: return kProductIds[2];
    case 24: return kProductIds[3];
    default: return 0;
  }
}

int channels_for_product_id(std::uint16_t product_id) noexcept {
  for (const int n : {6, 12, 18, 24})
    if (product_id_for_channels(n) == product_id) return n;
  return 0;
}

SetupPacket set_target(std::uint8_t channel, std::uint16_t quarter_us) noexcept {
  return {kVendorOut, kSetTarget, quarter_us, channel, 0};
}

SetupPacket set_speed(std::uint8_t channel, std::uint16_t speed) noexcept {
  return {kVendorOut, kSetServoVariable, speed, channel, 0};
}

SetupPacket set_acceleration(std::uint8_t channel, std::uint16_t acceleration) noexcept {
  return {kVendorOut, kSetServoVariable, std::min(acceleration, maestro::kMaxAcceleration),
          static_cast<std::uint16_t>(channel | kAccelerationFlag), 0};
}

SetupPacket clear_errors() noexcept { return {kVendorOut, kClearErrors, 0, 0, 0}; }

SetupPacket get_variables(int channel_count) noexcept {
  const std::size_t length = is_micro(channel_count) ? kMicroVariablesSize + 6 * kServoRecordSize : kMiniVariablesSize;
  return {kVendorIn, kGetVariables, 0, 0, static_cast<std::uint16_t>(length)};
}

SetupPacket get_servo_settings(int channel_count) noexcept {
  return {kVendorIn, kGetServoSettings, 0, 0, static_cast<std::uint16_t>(channel_count * kServoRecordSize)};
}

SetupPacket get_positions(int channel_count) noexcept {
  return is_micro(channel_count) ? get_variables(channel_count) : get_servo_settings(channel_count);
}

void encode_servo_status(std::span<std::uint8_t> out, const ServoStatus& status) noexcept {
  put_u16_le(&out[0], status.position);
  put_u16_le(&out[2], status.target);
  put_u16_le(&out[4], status.speed);
  out[6] = status.acceleration;
}

bool decode_servo_status(std::span<const std::uint8_t> reply, int channel_count, int channel, ServoStatus* out) noexcept {
  if (channel < 0) return false;
  const std::size_t at = records_offset(channel_count) + static_cast<std::size_t>(channel) * kServoRecordSize;
  if (reply.size() < at + kServoRecordSize) return false;
  out->position = get_u16_le(&reply[at]);
  out->target = get_u16_le(&reply[at + 2]);
  out->speed = get_u16_le(&reply[at + 4]);
  out->acceleration = reply[at + 6];
  return true;
}

bool decode_errors(std::span<const std::uint8_t> reply, std::uint16_t* errors) noexcept {
  if (reply.size() < kMiniVariablesSize) return false;
  *errors = get_u16_le(&reply[kErrorsOffset]);
  return true;
}

}  // namespace avar::firmware_iface::maestro_usb
