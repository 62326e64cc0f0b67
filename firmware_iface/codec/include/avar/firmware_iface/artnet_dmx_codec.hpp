#pragma once
// ArtDmx (Art-Net 4, OpCode 0x5000): one universe of DMX512 slots. Layout after the versioned
// header (artnet_header.hpp): Sequence (1..255, 0 = not used), Physical (the input port the
// data came from, informative), SubUni (low byte of the 15-bit Port-Address: Sub-Net in the high
// nibble, Universe in the low nibble), Net (bits 14..8 of the Port-Address), Length (big-endian,
// even, 2..512), then Length slots (slot 1 first; the start code is implied 0).
// Pure: no allocation, exception or I/O; real-time safe.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "avar/firmware_iface/artnet_header.hpp"

namespace avar::firmware_iface::artnet {

inline constexpr std::size_t kDmxHeaderSize = 18;
inline constexpr std::size_t kMaxDmxSlots = 512;
inline constexpr std::size_t kMaxDmxPacketSize = kDmxHeaderSize + kMaxDmxSlots;
inline constexpr std::uint16_t kMaxPortAddress = 0x7FFF;

/// The 15-bit Port-Address of Net (0..127), Sub-Net (0..15) and Universe (0..15); values out of
/// range are masked.
constexpr std::uint16_t port_address(unsigned net, unsigned sub_net, unsigned universe) noexcept {
  return static_cast<std::uint16_t>(((net & 0x7FU) << 8U) | ((sub_net & 0x0FU) << 4U) | (universe & 0x0FU));
}

/// Bytes of an ArtDmx packet carrying `slots` slots (an odd count is padded to even, at least 2).
constexpr std::size_t dmx_packet_size(std::size_t slots) noexcept {
  const std::size_t even = slots < 2 ? 2 : slots + (slots & 1U);
  return kDmxHeaderSize + even;
}

struct DmxPacket {
  std::uint8_t sequence = 0;
  std::uint8_t physical = 0;
  std::uint16_t port_address = 0;       ///< 0..32767
  std::span<const std::uint8_t> slots;  ///< points into the datagram; even length 2..512
};

/// Writes an ArtDmx packet; an odd slot count (or a single slot) is padded with zero slots to
/// an even length. Returns the bytes written, or 0 when `out` is too small, `slots` is empty or
/// longer than 512, or `port_address` exceeds 32767.
std::size_t encode_dmx(std::span<std::uint8_t> out, std::uint8_t sequence, std::uint8_t physical, std::uint16_t port_address,
                       std::span<const std::uint8_t> slots) noexcept;

/// Reads an ArtDmx packet; nullopt for anything else or anything malformed: not Art-Net, another
/// OpCode, protocol version below 14, shorter than its header, Net with bit 7 set, a length that
/// is odd, outside 2..512 or disagrees with the datagram's size.
std::optional<DmxPacket> decode_dmx(std::span<const std::uint8_t> datagram) noexcept;

}  // namespace avar::firmware_iface::artnet
