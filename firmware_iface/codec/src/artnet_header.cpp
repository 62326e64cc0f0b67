#include "avar/firmware_iface/artnet_header.hpp"

#include <algorithm>
#include <array>

namespace avar::firmware_iface::artnet {
namespace {

constexpr std::array<std::uint8_t, kIdSize> kId{'A', 'r', 't', '-', 'N', 'e', 't', 0};

}  // namespace

std::size_t write_header(OpCode op, bool versioned, std::span<std::uint8_t> out) noexcept {
  const std::size_t size = versioned ? kVersionedHeaderSize : kOpCodeHeaderSize;
  if (out.size() < size) return 0;
  std::copy(kId.begin(), kId.end(), out.begin());
  const auto code = static_cast<std::uint16_t>(op);
  out[8] = static_cast<std::uint8_t>(code & 0xFFU);
  out[9] = static_cast<std::uint8_t>(code >> 8U);
  if (versioned) {
    out[10] = static_cast<std::uint8_t>(kProtocolVersion >> 8U);
    out[11] = static_cast<std::uint8_t>(kProtocolVersion & 0xFFU);
  }
  return size;
}

std::optional<std::uint16_t> read_opcode(std::span<const std::uint8_t> datagram) noexcept {
  if (datagram.size() < kOpCodeHeaderSize || !std::equal(kId.begin(), kId.end(), datagram.begin())) {
    return std::nullopt;
  }
  return static_cast<std::uint16_t>(datagram[8] | (datagram[9] << 8U));
}

bool supported_version(std::span<const std::uint8_t> datagram) noexcept {
  if (datagram.size() < kVersionedHeaderSize) return false;
  return ((datagram[10] << 8U) | datagram[11]) >= kProtocolVersion;
}

}  // namespace avar::firmware_iface::artnet
