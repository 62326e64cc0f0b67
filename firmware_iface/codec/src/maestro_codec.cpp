// The Maestro codec's freestanding part (C++14, no standard library): framing, CRC, replies.
#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar {
namespace firmware_iface {
namespace maestro {
namespace {

/// Writes header + payload (+ CRC) and returns the length, or 0 if it does not fit.
size_t frame(uint8_t* out, size_t room, const Framing& f, uint8_t command, const uint8_t* head, size_t head_size,
             const uint16_t* values14 = nullptr, size_t value_count = 0) noexcept {
  if (f.pololu && f.device_number > 127) return 0;
  const size_t size = (f.pololu ? 3u : 1u) + head_size + 2 * value_count + (f.crc ? 1u : 0u);
  if (room < size) return 0;
  size_t n = 0;
  if (f.pololu) {
    out[n++] = kPololuStart;
    out[n++] = f.device_number;
    out[n++] = static_cast<uint8_t>(command & 0x7F);
  } else {
    out[n++] = command;
  }
  for (size_t i = 0; i < head_size; ++i) out[n++] = head[i];
  for (size_t i = 0; i < value_count; ++i) {
    const uint16_t s = values14[i] < kMaxValue ? values14[i] : kMaxValue;
    out[n++] = static_cast<uint8_t>(s & 0x7F);
    out[n++] = static_cast<uint8_t>((s >> 7) & 0x7F);
  }
  if (f.crc) {
    out[n] = crc7(out, n);
    ++n;
  }
  return n;
}

bool valid_channel(uint8_t channel) noexcept { return channel < kMaxChannels; }

uint16_t u16_le(const uint8_t* bytes) noexcept { return static_cast<uint16_t>(bytes[0] | (bytes[1] << 8)); }

}  // namespace

size_t encode_set_target(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t quarter_us) noexcept {
  if (!valid_channel(channel)) return 0;
  return frame(out, room, f, kSetTarget, &channel, 1, &quarter_us, 1);
}

size_t encode_set_multiple_targets(uint8_t* out, size_t room, const Framing& f, uint8_t first_channel, const uint16_t* quarter_us,
                                   size_t count) noexcept {
  if (count == 0 || count > kMaxChannels || !valid_channel(first_channel) || first_channel + count > kMaxChannels) return 0;
  const uint8_t head[2] = {static_cast<uint8_t>(count), first_channel};
  return frame(out, room, f, kSetMultipleTargets, head, 2, quarter_us, count);
}

size_t encode_set_speed(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t speed) noexcept {
  if (!valid_channel(channel)) return 0;
  return frame(out, room, f, kSetSpeed, &channel, 1, &speed, 1);
}

size_t encode_set_acceleration(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t acceleration) noexcept {
  if (!valid_channel(channel)) return 0;
  const uint16_t value = acceleration < kMaxAcceleration ? acceleration : kMaxAcceleration;
  return frame(out, room, f, kSetAcceleration, &channel, 1, &value, 1);
}

size_t encode_get_position(uint8_t* out, size_t room, const Framing& f, uint8_t channel) noexcept {
  if (!valid_channel(channel)) return 0;
  return frame(out, room, f, kGetPosition, &channel, 1);
}

size_t encode_get_moving_state(uint8_t* out, size_t room, const Framing& f) noexcept {
  return frame(out, room, f, kGetMovingState, nullptr, 0);
}

size_t encode_get_errors(uint8_t* out, size_t room, const Framing& f) noexcept {
  return frame(out, room, f, kGetErrors, nullptr, 0);
}

size_t encode_go_home(uint8_t* out, size_t room, const Framing& f) noexcept { return frame(out, room, f, kGoHome, nullptr, 0); }

size_t encode_mini_ssc(uint8_t* out, size_t room, uint8_t address, uint8_t target8) noexcept {
  if (room < 3 || address > 254 || target8 > 254) return 0;
  out[0] = kMiniSscStart;
  out[1] = address;
  out[2] = target8;
  return 3;
}

uint8_t crc7(const uint8_t* bytes, size_t length) noexcept {
  uint8_t crc = 0;
  for (size_t i = 0; i < length; ++i) {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit) crc = static_cast<uint8_t>((crc & 1) ? (crc ^ 0x91) >> 1 : crc >> 1);
  }
  return static_cast<uint8_t>(crc & 0x7F);
}

uint16_t decode_position_reply(const uint8_t* reply) noexcept { return u16_le(reply); }

bool decode_moving_state_reply(const uint8_t* reply) noexcept { return reply[0] != 0; }

uint16_t decode_errors_reply(const uint8_t* reply) noexcept { return u16_le(reply); }

}  // namespace maestro
}  // namespace firmware_iface
}  // namespace avar
