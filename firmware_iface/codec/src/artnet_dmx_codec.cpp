#include "avar/firmware_iface/artnet_dmx_codec.hpp"

#include <algorithm>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::artnet {

std::size_t encode_dmx(std::span<std::uint8_t> out, std::uint8_t sequence, std::uint8_t physical, std::uint16_t port_address,
                       std::span<const std::uint8_t> slots) noexcept {
  if (slots.empty() || slots.size() > kMaxDmxSlots || port_address > kMaxPortAddress) return 0;
  const std::size_t size = dmx_packet_size(slots.size());
  if (out.size() < size) return 0;
  write_header(OpCode::dmx, true, out);
  out[12] = sequence;
  out[13] = physical;
  put_u16_le(&out[14], port_address);
  const std::size_t length = size - kDmxHeaderSize;
  put_u16_be(&out[16], static_cast<std::uint16_t>(length));
  const auto data = out.subspan(kDmxHeaderSize, length);
  std::copy(slots.begin(), slots.end(), data.begin());
  std::fill(data.begin() + static_cast<std::ptrdiff_t>(slots.size()), data.end(), std::uint8_t{0});
  return size;
}

std::optional<DmxPacket> decode_dmx(std::span<const std::uint8_t> datagram) noexcept {
  if (read_opcode(datagram) != static_cast<std::uint16_t>(OpCode::dmx) || datagram.size() < kDmxHeaderSize ||
      !supported_version(datagram) || (datagram[15] & 0x80U) != 0)
    return std::nullopt;
  const std::size_t length = get_u16_be(&datagram[16]);
  if (length < 2 || length > kMaxDmxSlots || (length & 1U) != 0 || datagram.size() != kDmxHeaderSize + length)
    return std::nullopt;
  DmxPacket p;
  p.sequence = datagram[12];
  p.physical = datagram[13];
  p.port_address = get_u16_le(&datagram[14]);
  p.slots = datagram.subspan(kDmxHeaderSize, length);
  return p;
}

}  // namespace avar::firmware_iface::artnet
