#pragma once
// ROBOTIS DYNAMIXEL Protocol 2.0 (../shared/protocols/dynamixel-2.md): pure encoders and
// decoders. No I/O, no clock, no allocation, no exception: every function is real-time safe.
// Encoders build one instruction packet into `out` (header, ID, length, instruction, byte-stuffed
// parameters, CRC-16) and return its length, or 0 when `out` is too small or an argument is
// invalid. Multi-byte values are little-endian.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::dynamixel {

inline constexpr std::uint8_t kBroadcastId = 0xFE;
inline constexpr std::uint8_t kMaxId = 252;

enum Instruction : std::uint8_t {
  kPing = 0x01,
  kRead = 0x02,
  kWrite = 0x03,
  kRegWrite = 0x04,
  kAction = 0x05,
  kFactoryReset = 0x06,
  kReboot = 0x08,
  kClear = 0x10,
  kStatus = 0x55,
  kSyncRead = 0x82,
  kSyncWrite = 0x83,
  kBulkRead = 0x92,
  kBulkWrite = 0x93,
};

/// X-series control table addresses avar uses.
enum Address : std::uint16_t {
  kModelNumber = 0,
  kId = 7,
  kBaudRate = 8,
  kReturnDelayTime = 9,
  kOperatingMode = 11,
  kTorqueEnable = 64,
  kLed = 65,
  kStatusReturnLevel = 68,
  kHardwareErrorStatus = 70,
  kProfileAcceleration = 108,
  kProfileVelocity = 112,
  kGoalPosition = 116,
  kPresentLoad = 126,
  kPresentPosition = 132,
  kPresentTemperature = 146,
};

/// CRC-16 of Protocol 2.0: polynomial 0x8005, initial 0, MSB first, no reflection.
std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept;

/// Builds any instruction packet from raw (unstuffed) parameters; the building block of the
/// encoders below.
std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params) noexcept;

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) noexcept;
std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address, std::uint16_t length) noexcept;
std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                         std::span<const std::uint8_t> data) noexcept;
std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id) noexcept;
std::size_t encode_reboot(std::span<std::uint8_t> out, std::uint8_t id) noexcept;
/// mode: 0xFF everything, 0x01 all but ID, 0x02 all but ID and baud rate.
std::size_t encode_factory_reset(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t mode) noexcept;
/// Sync Read of `length` bytes at `address` from each of `ids` (broadcast packet).
std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids) noexcept;
/// Sync Write of one 4-byte signed value at `address` to each of `ids` (values[i] for ids[i]).
std::size_t encode_sync_write_u32(std::span<std::uint8_t> out, std::uint16_t address, std::span<const std::uint8_t> ids,
                                  std::span<const std::int32_t> values) noexcept;

/// A status packet, decoded.
struct Status {
  std::uint8_t id = 0;
  std::uint8_t error = 0;                ///< bit 7: alert (hardware error latched); bits 0-6: processing error
  std::span<const std::uint8_t> params;  ///< unstuffed, pointing into the caller's scratch buffer
  bool alert() const noexcept { return error & 0x80; }
  std::uint8_t processing_error() const noexcept { return error & 0x7F; }
};

// clang-format 14 misreads an attribute on an enum and indents it:
// clang-format off
enum class [[nodiscard]] DecodeResult {
  ok,
  need_more,     ///< a packet has started but is not complete yet
  bad_crc,       ///< a whole packet arrived with a wrong CRC (consume it and go on)
  bad_framing,   ///< no header, or a length that cannot be (resynchronise past the first byte)
  not_status,    ///< a well-formed packet that is not a status packet
};
// clang-format on

/// Any packet, decoded: instruction packets as a device receives them, status packets as the
/// host does. For a status packet, params start with the error byte.
struct Packet {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::span<const std::uint8_t> params;  ///< unstuffed, pointing into the caller's scratch buffer
};

/// Looks for one packet at the start of `in`; the same results and consumption rules as
/// decode_status, without the status check (never returns not_status).
DecodeResult decode_packet(std::span<const std::uint8_t> in, std::span<std::uint8_t> scratch, Packet* packet,
                           std::size_t* consumed) noexcept;

/// Looks for one status packet at the start of `in` (after skipping anything before the first
/// header, reported in *consumed). On ok, bad_crc and not_status, *consumed covers the whole
/// packet. Parameters are unstuffed into `scratch` (which must be at least as large as the
/// packet) and `status->params` points into it.
DecodeResult decode_status(std::span<const std::uint8_t> in, std::span<std::uint8_t> scratch, Status* status,
                           std::size_t* consumed) noexcept;

/// Names of processing error numbers and hardware error bits, for messages (allocates).
std::string describe_processing_error(std::uint8_t error);
std::string describe_hardware_error(std::uint8_t bits);

/// A control-table value (little-endian, avar/core/byte_order.hpp) at the start of `p`.
inline std::int32_t read_i32(std::span<const std::uint8_t> p) noexcept { return get_i32_le(p.data()); }
inline std::uint16_t read_u16(std::span<const std::uint8_t> p) noexcept { return get_u16_le(p.data()); }

}  // namespace avar::firmware_iface::dynamixel
