#pragma once
// The header every Art-Net packet starts with (Art-Net 4 specification, Artistic Licence): the
// 8-byte ID "Art-Net\0", the OpCode (16 bits, little-endian) and, for every packet but
// ArtPollReply, the protocol version (16 bits, big-endian, 14). Each packet's codec (ArtDmx,
// ArtPoll, ArtPollReply, ArtTimeCode) builds on these. Pure: no allocation, exception or I/O.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace avar::firmware_iface::artnet {

inline constexpr std::uint16_t kUdpPort = 6454;
inline constexpr std::uint16_t kProtocolVersion = 14;
inline constexpr std::size_t kIdSize = 8;
/// ID and OpCode.
inline constexpr std::size_t kOpCodeHeaderSize = 10;
/// ID, OpCode and protocol version.
inline constexpr std::size_t kVersionedHeaderSize = 12;

enum class OpCode : std::uint16_t {
  poll = 0x2000,
  poll_reply = 0x2100,
  dmx = 0x5000,
  sync = 0x5200,
  time_code = 0x9700,
};

/// Writes the ID and `op` into out[0..10) and, when `versioned`, the protocol version into
/// out[10..12). Returns the bytes written, or 0 when `out` is too small.
std::size_t write_header(OpCode op, bool versioned, std::span<std::uint8_t> out) noexcept;

/// The OpCode of a datagram that starts with the Art-Net ID, whatever its value; nullopt when
/// the datagram is too short or is not Art-Net.
std::optional<std::uint16_t> read_opcode(std::span<const std::uint8_t> datagram) noexcept;

/// True when a versioned packet's protocol version (bytes 10..12, big-endian) is at least 14,
/// as receivers must check.
bool supported_version(std::span<const std::uint8_t> datagram) noexcept;

}  // namespace avar::firmware_iface::artnet
