#pragma once
// Pololu Maestro serial protocol (shared/protocols/pololu-maestro.md): pure encoders and
// decoders. No I/O, no clock, no allocation, no exception: every function except
// describe_errors() is real-time safe and may be called from any thread.
//
// One source for the host's links and the device engine's players: the encoders, the CRC and the
// decoders are freestanding C++14 (<stdint.h> and <stddef.h> only) on a pointer and the room
// behind it; a C++20 build (the host) adds the same functions on std::span, the unit conversions
// (double) and describe_errors (maestro_units.cpp).
//
// Encoders write one packet into `out` and return its length, or 0 (writing nothing) when `out`
// is too small or an argument is invalid: a channel above 23, an empty or too long target list,
// a Pololu device number above 127. 14-bit values saturate at 16383, never wrap.
//
// Packet sizes: compact `cmd, data…`; Pololu adds 2 bytes (`0xAA, device`, then the command
// with bit 7 cleared); CRC mode adds 1 byte at the end.
//   Set Target / Set Speed / Set Acceleration   4 compact, 6 Pololu (+1 CRC)
//   Set Multiple Targets for n channels          3 + 2n compact, 5 + 2n Pololu (+1 CRC)
//   Get Position                                 2 compact, 4 Pololu (+1 CRC)
//   Get Moving State / Get Errors / Go Home      1 compact, 3 Pololu (+1 CRC)
//   Mini SSC                                     3 (never a CRC)
// A buffer of kMaxPacketSize bytes holds any packet.

#include <stddef.h>
#include <stdint.h>
#if __cplusplus >= 202002L
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#endif

namespace avar {
namespace firmware_iface {
namespace maestro {

/// How packets are framed: compact (`cmd, data…`) or Pololu (`0xAA, device, cmd & 0x7F,
/// data…`), with an optional CRC-7 byte at the end (the device's "Enable CRC" setting).
struct Framing {
  bool pololu = false;
  uint8_t device_number = 12;  ///< 0..127; used only in the Pololu form
  bool crc = false;
};

/// Channels of the largest Maestro (Mini 24): valid channels are 0..23.
const int kMaxChannels = 24;
/// Largest packet any encoder writes: Set Multiple Targets for 24 channels, Pololu form, CRC.
const size_t kMaxPacketSize = 3 + 2 + 2 * kMaxChannels + 1;
/// Largest 14-bit value (two 7-bit data bytes).
const uint16_t kMaxValue = 0x3FFF;
/// Largest acceleration the device takes.
const uint16_t kMaxAcceleration = 255;
/// Reply sizes in bytes (replies carry no framing and no CRC).
const size_t kPositionReplySize = 2;
const size_t kMovingStateReplySize = 1;
const size_t kErrorsReplySize = 2;

/// Command bytes in their compact form (the Pololu form sends them with bit 7 cleared).
enum Command : uint8_t {
  kSetTarget = 0x84,
  kSetSpeed = 0x87,
  kSetAcceleration = 0x89,
  kSetPwm = 0x8A,  ///< Mini 12/18/24 only
  kGetPosition = 0x90,
  kGetMovingState = 0x93,
  kSetMultipleTargets = 0x9F,  ///< Mini 12/18/24 only
  kGetErrors = 0xA1,
  kGoHome = 0xA2,
  kStopScript = 0xA4,
  kRestartScript = 0xA7,
  kRestartScriptWithParameter = 0xA8,
  kGetScriptStatus = 0xAE,
  kPololuStart = 0xAA,   ///< first byte of the Pololu form, and the baud-detection byte
  kMiniSscStart = 0xFF,  ///< first byte of the Mini SSC form
};

/// Bits of the error register.
enum ErrorBit : uint16_t {
  kSerialSignalError = 1u << 0,
  kSerialOverrunError = 1u << 1,
  kSerialRxBufferFull = 1u << 2,
  kSerialCrcError = 1u << 3,
  kSerialProtocolError = 1u << 4,
  kSerialTimeout = 1u << 5,
  kScriptStackError = 1u << 6,
  kScriptCallStackError = 1u << 7,
  kScriptProgramCounterError = 1u << 8,
};

// The freestanding forms: `out` has `room` bytes.

/// Set Target: channel 0..23, target in quarter-µs (0 = stop pulses; saturates at 16383).
size_t encode_set_target(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t quarter_us) noexcept;
/// Set Multiple Targets (Mini Maestro only): quarter_us[i] goes to channel first_channel + i.
/// 1 to 24 targets, the last channel at most 23.
size_t encode_set_multiple_targets(uint8_t* out, size_t room, const Framing& f, uint8_t first_channel, const uint16_t* quarter_us,
                                   size_t count) noexcept;
/// Set Speed: speed in units of 0.25 µs per 10 ms = 25 µs/s (0 = unlimited; saturates at
/// 16383, and the device itself caps it at 10000).
size_t encode_set_speed(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t speed) noexcept;
/// Set Acceleration: units of 0.25 µs per 10 ms per 80 ms = 312.5 µs/s² (0 = unlimited;
/// saturates at 255).
size_t encode_set_acceleration(uint8_t* out, size_t room, const Framing& f, uint8_t channel, uint16_t acceleration) noexcept;
/// Get Position: the device answers kPositionReplySize bytes (decode_position_reply).
size_t encode_get_position(uint8_t* out, size_t room, const Framing& f, uint8_t channel) noexcept;
/// Get Moving State: the device answers kMovingStateReplySize bytes.
size_t encode_get_moving_state(uint8_t* out, size_t room, const Framing& f) noexcept;
/// Get Errors: the device answers kErrorsReplySize bytes and clears its error register.
size_t encode_get_errors(uint8_t* out, size_t room, const Framing& f) noexcept;
/// Go Home: every channel goes to its configured home position.
size_t encode_go_home(uint8_t* out, size_t room, const Framing& f) noexcept;
/// Mini SSC: `0xFF, address, target8`; address = channel + the device's Mini SSC offset, 0..254;
/// target8 0..254 (127 = the channel's 8-bit neutral). Never carries a CRC.
size_t encode_mini_ssc(uint8_t* out, size_t room, uint8_t address, uint8_t target8) noexcept;

/// CRC-7 of a packet: polynomial 0x91 processed LSB first, initial 0; result 0..127. The CRC
/// byte covers the whole packet, including 0xAA and the device number in the Pololu form.
uint8_t crc7(const uint8_t* bytes, size_t length) noexcept;

/// Get Position reply (kPositionReplySize bytes): the output pulse in quarter-µs (little-endian,
/// full 8-bit bytes).
uint16_t decode_position_reply(const uint8_t* reply) noexcept;
/// Get Moving State reply (kMovingStateReplySize bytes): true when at least one servo is still moving.
bool decode_moving_state_reply(const uint8_t* reply) noexcept;
/// Get Errors reply (kErrorsReplySize bytes): error bits 0..15 (little-endian); see ErrorBit.
uint16_t decode_errors_reply(const uint8_t* reply) noexcept;

#if __cplusplus >= 202002L
// The host's forms on spans (the same functions), and what needs double or std::string.

inline std::size_t encode_set_target(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                                     std::uint16_t quarter_us) noexcept {
  return encode_set_target(out.data(), out.size(), f, channel, quarter_us);
}
inline std::size_t encode_set_multiple_targets(std::span<std::uint8_t> out, const Framing& f, std::uint8_t first_channel,
                                               std::span<const std::uint16_t> quarter_us) noexcept {
  return encode_set_multiple_targets(out.data(), out.size(), f, first_channel, quarter_us.data(), quarter_us.size());
}
inline std::size_t encode_set_speed(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                                    std::uint16_t speed) noexcept {
  return encode_set_speed(out.data(), out.size(), f, channel, speed);
}
inline std::size_t encode_set_acceleration(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                                           std::uint16_t acceleration) noexcept {
  return encode_set_acceleration(out.data(), out.size(), f, channel, acceleration);
}
inline std::size_t encode_get_position(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel) noexcept {
  return encode_get_position(out.data(), out.size(), f, channel);
}
inline std::size_t encode_get_moving_state(std::span<std::uint8_t> out, const Framing& f) noexcept {
  return encode_get_moving_state(out.data(), out.size(), f);
}
inline std::size_t encode_get_errors(std::span<std::uint8_t> out, const Framing& f) noexcept {
  return encode_get_errors(out.data(), out.size(), f);
}
inline std::size_t encode_go_home(std::span<std::uint8_t> out, const Framing& f) noexcept {
  return encode_go_home(out.data(), out.size(), f);
}
inline std::size_t encode_mini_ssc(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t target8) noexcept {
  return encode_mini_ssc(out.data(), out.size(), address, target8);
}
inline std::uint8_t crc7(std::span<const std::uint8_t> bytes) noexcept { return crc7(bytes.data(), bytes.size()); }
inline std::uint16_t decode_position_reply(std::span<const std::uint8_t, kPositionReplySize> reply) noexcept {
  return decode_position_reply(reply.data());
}
inline bool decode_moving_state_reply(std::span<const std::uint8_t, kMovingStateReplySize> reply) noexcept {
  return decode_moving_state_reply(reply.data());
}
inline std::uint16_t decode_errors_reply(std::span<const std::uint8_t, kErrorsReplySize> reply) noexcept {
  return decode_errors_reply(reply.data());
}

/// Names of the set bits, lowest first, comma-separated ("none" for 0; bits the protocol does
/// not name read "error bit N"). Allocates: not for the tick.
std::string describe_errors(std::uint16_t errors);

/// Pulse width in µs to quarter-µs, rounded to nearest, saturating to 0..16383 (NaN and values
/// <= 0 give 0, which the device reads as "no pulses").
std::uint16_t quarter_us_from_us(double us) noexcept;
/// Quarter-µs to µs (exact).
double us_from_quarter_us(std::uint16_t quarter_us) noexcept;
/// Speed limit in µs/s to device units of 25 µs/s, rounded down so the device is never faster
/// than asked, saturating to 1..16383 (never 0, which means "unlimited"; NaN gives 1).
std::uint16_t speed_units_from_us_per_s(double us_per_s) noexcept;
/// Acceleration limit in µs/s² to device units of 312.5 µs/s², rounded down, saturating to
/// 1..255 (never 0, which means "unlimited"; NaN gives 1).
std::uint16_t acceleration_units_from_us_per_s2(double us_per_s2) noexcept;
/// Device speed units to µs/s (0 means unlimited and gives 0).
double us_per_s_from_speed_units(std::uint16_t speed) noexcept;
/// Device acceleration units to µs/s² (0 means unlimited and gives 0).
double us_per_s2_from_acceleration_units(std::uint16_t acceleration) noexcept;

#endif

}  // namespace maestro
}  // namespace firmware_iface
}  // namespace avar
