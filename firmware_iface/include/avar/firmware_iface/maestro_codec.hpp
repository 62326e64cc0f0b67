#pragma once
// Pololu Maestro serial protocol (../shared/protocols/pololu-maestro.md): pure encoders and
// decoders. No I/O, no clock, no allocation, no exception: every function is real-time safe.
// Encoders write one packet into `out` and return its length, or 0 when `out` is too small or
// an argument is invalid. 14-bit values saturate at 16383, never wrap.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace avar::firmware_iface::maestro {

/// How packets are framed: compact (`cmd, data…`) or Pololu (`0xAA, device, cmd & 0x7F,
/// data…`), with an optional CRC-7 byte at the end (the device's "Enable CRC" setting).
struct Framing {
  bool pololu = false;
  std::uint8_t device_number = 12;  ///< 0..127
  bool crc = false;
};

inline constexpr int kMaxChannels = 24;
/// Largest packet any encoder writes: Set Multiple Targets for 24 channels, Pololu form, CRC.
inline constexpr std::size_t kMaxPacketSize = 2 + 3 + 2 * kMaxChannels + 1;
inline constexpr std::uint16_t kMaxValue = 0x3FFF;

enum Command : std::uint8_t {
  kSetTarget = 0x84,
  kSetSpeed = 0x87,
  kSetAcceleration = 0x89,
  kSetPwm = 0x8A,
  kGetPosition = 0x90,
  kGetMovingState = 0x93,
  kSetMultipleTargets = 0x9F,
  kGetErrors = 0xA1,
  kGoHome = 0xA2,
  kPololuStart = 0xAA,
  kMiniSscStart = 0xFF,
};

std::size_t encode_set_target(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel, std::uint16_t quarter_us) noexcept;
/// Consecutive channels from first_channel; 1 to 24 targets, all within channel 23.
std::size_t encode_set_multiple_targets(std::span<std::uint8_t> out, const Framing& f, std::uint8_t first_channel,
                                        std::span<const std::uint16_t> quarter_us) noexcept;
/// speed in units of 0.25 µs per 10 ms (0 = unlimited).
std::size_t encode_set_speed(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel, std::uint16_t speed) noexcept;
/// acceleration in units of 0.25 µs per 10 ms per 80 ms, 0..255 (0 = unlimited).
std::size_t encode_set_acceleration(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel,
                                    std::uint16_t acceleration) noexcept;
std::size_t encode_get_position(std::span<std::uint8_t> out, const Framing& f, std::uint8_t channel) noexcept;
std::size_t encode_get_moving_state(std::span<std::uint8_t> out, const Framing& f) noexcept;
std::size_t encode_get_errors(std::span<std::uint8_t> out, const Framing& f) noexcept;
std::size_t encode_go_home(std::span<std::uint8_t> out, const Framing& f) noexcept;
/// Mini SSC: `0xFF, address, target8`; address = channel + the device's Mini SSC offset, 0..254;
/// target8 0..254 (127 = neutral). Never carries a CRC.
std::size_t encode_mini_ssc(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t target8) noexcept;

/// CRC-7 of a packet: polynomial 0x91 processed LSB first, initial 0; result 0..127.
std::uint8_t crc7(std::span<const std::uint8_t> bytes) noexcept;

/// Get Position reply: the output pulse in quarter-µs (little-endian, full 8-bit bytes).
std::uint16_t decode_position_reply(std::span<const std::uint8_t, 2> reply) noexcept;
/// Get Moving State reply: true when at least one servo is still moving.
bool decode_moving_state_reply(std::span<const std::uint8_t, 1> reply) noexcept;
/// Get Errors reply: error bits 0..15 (little-endian).
std::uint16_t decode_errors_reply(std::span<const std::uint8_t, 2> reply) noexcept;

/// Bits of the error register.
enum ErrorBit : std::uint16_t {
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

/// Names of the set bits, comma-separated ("none" for 0). Allocates: not for the tick.
std::string describe_errors(std::uint16_t errors);

/// Unit conversions, saturating into the protocol's ranges.
std::uint16_t quarter_us_from_us(double us) noexcept;                     ///< 0..16383
std::uint16_t speed_units_from_us_per_s(double us_per_s) noexcept;        ///< 25 µs/s per unit, 1..16383
std::uint16_t acceleration_units_from_us_per_s2(double us_per_s2) noexcept;  ///< 312.5 µs/s² per unit, 1..255
double us_per_s_from_speed_units(std::uint16_t speed) noexcept;
double us_per_s2_from_acceleration_units(std::uint16_t acceleration) noexcept;

}  // namespace avar::firmware_iface::maestro
