#include "avar/firmware_iface/artnet_header.hpp"

#include <algorithm>
#include <array>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::artnet {
namespace {

constexpr std::array<std::uint8_t, kIdSize> kId{'A', 'r', 't', '-', 'N', 'e', 't', 0};

}  // namespace

std::size_t write_header(OpCode op, bool versioned, std::span<std::uint8_t> out) noexcept {
  const std::size_t size = versioned ? kVersionedHeaderSize : kOpCodeHeaderSize;
  if (out.size() < size) return 0;
  std::copy(kId.begin(), kId.end(), out.begin());
  const auto code = static_cast<std::uint16_t>(op);
  put_u16_le(&out[8], code);  // the OpCode is little-endian, the version big-endian
  if (versioned) put_u16_be(&out[10], kProtocolVersion);
  return size;
}

std::optional<std::uint16_t> read_opcode(std::span<const std::uint8_t> datagram) noexcept {
  if (datagram.size() < kOpCodeHeaderSize || !std::equal(kId.begin(), kId.end(), datagram.begin())) {
    return std::nullopt;
  }
  return get_u16_le(&datagram[8]);
}

bool supported_version(std::span<const std::uint8_t> datagram) noexcept {
  if (datagram.size() < kVersionedHeaderSize) return false;
  return get_u16_be(&datagram[10]) >= kProtocolVersion;
}

}  // namespace avar::firmware_iface::artnet
