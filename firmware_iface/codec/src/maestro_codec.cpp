#include "avar/firmware_iface/maestro_codec.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::maestro {
namespace {

/// Writes header + payload (+ CRC) and returns the length, or 0 if it does not fit.
std::size_t frame(std::span<std::uint8_t> out, const Framing& f, std::uint8_t command, std::initializer_list<std::uint8_t> head,
                  std::span<const std::uint16_t> values14 = {}) noexcept {
  if (f.pololu && f.device_number > 127) return 0;
  const std::size_t size = (f.pololu ? 3u : 1u) + head.size() + 2 * values14.size() + (f.crc ? 1u : 0u);
  if (out.size() < size) return 0;
  std::size_t n = 0;
  if (f.pololu) {
    out[n++] = kPololuStart;
    out[n++] = f.device_number;
    out[n++] = static_cast<std::uint8_t>(command & 0x7F);
  } else {
    out[n++] = command;
  }
  for (std::uint8_t b : head) out[n++] = b;
  for (std::uint16_t v : values14) {
    const std::uint16_t s = std::min(v, kMaxValue);
    out[n++] = static_cast<std::uint8_t>(s & 0x7F);
    out[n++] = static_cast<std::uint8_t>((s >> 7) & 0x7F);
  }
  if (f.crc) {
    out[n] = crc7(out.first(n));
    ++n;
  }
  return n;
}

bool valid_channel(std::uint8_t channel) noexcept { return channel < kMaxChannels; }

}  // namespace

std::size_t encode_set_target(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                              std::uint16_t quarter_us) noexcept {
  if (!valid_channel(channel)) return 0;
  const std::uint16_t v[1] = {quarter_us};
  return frame(out, f, kSetTarget, {channel}, v);
}

std::size_t encode_set_multiple_targets(std::span<std::uint8_t> out, const Framing& f, std::uint8_t first_channel,
                                        std::span<const std::uint16_t> quarter_us) noexcept {
  if (quarter_us.empty() || quarter_us.size() > kMaxChannels || !valid_channel(first_channel) ||
      first_channel + quarter_us.size() > kMaxChannels)
    return 0;
  return frame(out, f, kSetMultipleTargets, {static_cast<std::uint8_t>(quarter_us.size()), first_channel}, quarter_us);
}

std::size_t encode_set_speed(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel, std::uint16_t speed) noexcept {
  if (!valid_channel(channel)) return 0;
  const std::uint16_t v[1] = {speed};
  return frame(out, f, kSetSpeed, {channel}, v);
}

std::size_t encode_set_acceleration(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                                    std::uint16_t acceleration) noexcept {
  if (!valid_channel(channel)) return 0;
  const std::uint16_t v[1] = {std::min(acceleration, kMaxAcceleration)};
  return frame(out, f, kSetAcceleration, {channel}, v);
}

std::size_t encode_get_position(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel) noexcept {
  if (!valid_channel(channel)) return 0;
  return frame(out, f, kGetPosition, {channel});
}

std::size_t encode_get_moving_state(std::span<std::uint8_t> out, const Framing& f) noexcept {
  return frame(out, f, kGetMovingState, {});
}
std::size_t encode_get_errors(std::span<std::uint8_t> out, const Framing& f) noexcept { return frame(out, f, kGetErrors, {}); }
std::size_t encode_go_home(std::span<std::uint8_t> out, const Framing& f) noexcept { return frame(out, f, kGoHome, {}); }

std::size_t encode_mini_ssc(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t target8) noexcept {
  if (out.size() < 3 || address > 254 || target8 > 254) return 0;
  out[0] = kMiniSscStart;
  out[1] = address;
  out[2] = target8;
  return 3;
}

std::uint8_t crc7(std::span<const std::uint8_t> bytes) noexcept {
  std::uint8_t crc = 0;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int i = 0; i < 8; ++i) crc = static_cast<std::uint8_t>((crc & 1) ? (crc ^ 0x91) >> 1 : crc >> 1);
  }
  return static_cast<std::uint8_t>(crc & 0x7F);
}

std::uint16_t decode_position_reply(std::span<const std::uint8_t, 2> reply) noexcept { return get_u16_le(reply.data()); }

bool decode_moving_state_reply(std::span<const std::uint8_t, 1> reply) noexcept { return reply[0] != 0; }

std::uint16_t decode_errors_reply(std::span<const std::uint8_t, 2> reply) noexcept { return get_u16_le(reply.data()); }

std::string describe_errors(std::uint16_t errors) {
  static constexpr const char* kNames[] = {"serial signal error", "serial overrun error",    "serial RX buffer full",
                                           "serial CRC error",    "serial protocol error",   "serial timeout",
                                           "script stack error",  "script call stack error", "script program counter error"};
  std::string out;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (!(errors & (1u << bit))) continue;
    if (!out.empty()) out += ", ";
    out += bit < std::size(kNames) ? kNames[bit] : "error bit " + std::to_string(bit);
  }
  return out.empty() ? "none" : out;
}

std::uint16_t quarter_us_from_us(double us) noexcept {
  if (!(us > 0)) return 0;
  // Clamp before rounding: lround of a value beyond `long` (or of infinity) is undefined.
  return static_cast<std::uint16_t>(std::lround(std::min(us * 4.0, static_cast<double>(kMaxValue))));
}

double us_from_quarter_us(std::uint16_t quarter_us) noexcept { return quarter_us / 4.0; }

std::uint16_t speed_units_from_us_per_s(double us_per_s) noexcept {
  // 1 unit = 0.25 µs per 10 ms = 25 µs/s; round down so the device is never faster than asked,
  // but never to 0, which would mean "unlimited".
  if (!(us_per_s > 0)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::floor(us_per_s / 25.0), 1.0, static_cast<double>(kMaxValue)));
}

std::uint16_t acceleration_units_from_us_per_s2(double us_per_s2) noexcept {
  if (!(us_per_s2 > 0)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::floor(us_per_s2 / 312.5), 1.0, static_cast<double>(kMaxAcceleration)));
}

double us_per_s_from_speed_units(std::uint16_t speed) noexcept { return 25.0 * speed; }
double us_per_s2_from_acceleration_units(std::uint16_t acceleration) noexcept { return 312.5 * acceleration; }

}  // namespace avar::firmware_iface::maestro
