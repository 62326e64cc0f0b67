#include "avar/firmware_iface/sacn_codec.hpp"

#include <algorithm>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::sacn {
namespace {

constexpr std::array<std::uint8_t, 12> kAcnPacketIdentifier{0x41, 0x53, 0x43, 0x2D, 0x45, 0x31,
                                                            0x2E, 0x31, 0x37, 0x00, 0x00, 0x00};
constexpr std::uint32_t kVectorRootData = 0x00000004;
constexpr std::uint32_t kVectorRootExtended = 0x00000008;
constexpr std::uint32_t kVectorFramingData = 0x00000002;
constexpr std::uint32_t kVectorFramingDiscovery = 0x00000002;
constexpr std::uint32_t kVectorDiscoveryList = 0x00000001;
constexpr std::uint8_t kVectorDmpSetProperty = 0x02;
constexpr std::uint8_t kDmpAddressDataType = 0xA1;
constexpr std::size_t kFramingAt = 38;
constexpr std::size_t kDmpAt = 115;
constexpr std::size_t kDiscoveryLayerAt = 112;

/// A PDU's flags (0x7) and length: from `at` to the end of a packet of `total` bytes.
void put_flags_length(std::span<std::uint8_t> out, std::size_t at, std::size_t total) noexcept {
  put_u16_be(&out[at], static_cast<std::uint16_t>(0x7000U | ((total - at) & 0x0FFFU)));
}

bool flags_length_ok(std::span<const std::uint8_t> in, std::size_t at) noexcept {
  const std::uint16_t v = get_u16_be(&in[at]);
  return (v >> 12U) == 0x7 && (v & 0x0FFFU) == in.size() - at;
}

/// The root layer and the framing layer's vector and source name, common to both packets.
void put_root_and_source(std::span<std::uint8_t> out, std::size_t total, std::uint32_t root_vector, std::uint32_t framing_vector,
                         const Source& source) noexcept {
  std::fill_n(out.begin(), total, std::uint8_t{0});
  put_u16_be(&out[0], 0x0010);
  put_u16_be(&out[2], 0x0000);
  std::copy(kAcnPacketIdentifier.begin(), kAcnPacketIdentifier.end(), out.begin() + 4);
  put_flags_length(out, 16, total);
  put_u32_be(&out[18], root_vector);
  std::copy(source.cid.begin(), source.cid.end(), out.begin() + 22);
  put_flags_length(out, kFramingAt, total);
  put_u32_be(&out[40], framing_vector);
  const std::size_t name = std::min(source.name.size(), kSourceNameSize - 1);
  std::transform(source.name.begin(), source.name.begin() + static_cast<std::ptrdiff_t>(name), out.begin() + 44,
                 [](char c) { return static_cast<std::uint8_t>(c); });
}

/// Checks the root layer and framing vector, reads the CID and source name.
bool read_root_and_source(std::span<const std::uint8_t> in, std::size_t min_size, std::uint32_t root_vector,
                          std::uint32_t framing_vector, Cid& cid, std::string_view& name) noexcept {
  if (in.size() < min_size || get_u16_be(&in[0]) != 0x0010 || get_u16_be(&in[2]) != 0x0000 ||
      !std::equal(kAcnPacketIdentifier.begin(), kAcnPacketIdentifier.end(), in.begin() + 4) || !flags_length_ok(in, 16) ||
      get_u32_be(&in[18]) != root_vector || !flags_length_ok(in, kFramingAt) || get_u32_be(&in[40]) != framing_vector)
    return false;
  std::copy_n(in.begin() + 22, cid.size(), cid.begin());
  const auto field = in.subspan(44, kSourceNameSize);
  const auto nul = std::find(field.begin(), field.end(), std::uint8_t{0});
  if (nul == field.end()) return false;
  name = std::string_view(reinterpret_cast<const char*>(field.data()), static_cast<std::size_t>(nul - field.begin()));
  return true;
}

}  // namespace

std::size_t encode_data(std::span<std::uint8_t> out, const Source& source, const DataHeader& header,
                        std::span<const std::uint8_t> slots) noexcept {
  const std::size_t total = data_packet_size(slots.size());
  if (slots.size() > kMaxSlots || out.size() < total || header.universe < kMinUniverse || header.universe > kMaxUniverse ||
      header.priority > kMaxPriority)
    return 0;
  put_root_and_source(out, total, kVectorRootData, kVectorFramingData, source);
  out[108] = header.priority;
  put_u16_be(&out[109], header.sync_address);
  out[111] = header.sequence;
  out[112] = header.options;
  put_u16_be(&out[113], header.universe);
  put_flags_length(out, kDmpAt, total);
  out[117] = kVectorDmpSetProperty;
  out[118] = kDmpAddressDataType;
  put_u16_be(&out[119], 0x0000);
  put_u16_be(&out[121], 0x0001);
  put_u16_be(&out[123], static_cast<std::uint16_t>(1 + slots.size()));
  out[kDataHeaderSize] = header.start_code;
  std::copy(slots.begin(), slots.end(), out.begin() + static_cast<std::ptrdiff_t>(kDataHeaderSize + 1));
  return total;
}

std::optional<DataPacket> decode_data(std::span<const std::uint8_t> in) noexcept {
  DataPacket p;
  if (!read_root_and_source(in, kDataHeaderSize + 1, kVectorRootData, kVectorFramingData, p.cid, p.source_name))
    return std::nullopt;
  p.header.priority = in[108];
  p.header.sync_address = get_u16_be(&in[109]);
  p.header.sequence = in[111];
  p.header.options = in[112];
  p.header.universe = get_u16_be(&in[113]);
  const std::uint16_t count = get_u16_be(&in[123]);
  if (p.header.priority > kMaxPriority || p.header.universe < kMinUniverse || p.header.universe > kMaxUniverse ||
      !flags_length_ok(in, kDmpAt) || in[117] != kVectorDmpSetProperty || in[118] != kDmpAddressDataType ||
      get_u16_be(&in[119]) != 0 || get_u16_be(&in[121]) != 1 || count < 1 || count > 1 + kMaxSlots ||
      in.size() != kDataHeaderSize + count)
    return std::nullopt;
  p.header.start_code = in[kDataHeaderSize];
  p.slots = in.subspan(kDataHeaderSize + 1);
  return p;
}

std::size_t encode_discovery(std::span<std::uint8_t> out, const Source& source, std::uint8_t page, std::uint8_t last_page,
                             std::span<const std::uint16_t> universes) noexcept {
  const std::size_t total = kDiscoveryHeaderSize + 2 * universes.size();
  if (universes.size() > kMaxDiscoveryUniverses || out.size() < total || page > last_page ||
      std::adjacent_find(universes.begin(), universes.end(), [](std::uint16_t a, std::uint16_t b) { return a >= b; }) !=
          universes.end())
    return 0;
  put_root_and_source(out, total, kVectorRootExtended, kVectorFramingDiscovery, source);
  // 108..111 reserved, zero.
  put_flags_length(out, kDiscoveryLayerAt, total);
  put_u32_be(&out[114], kVectorDiscoveryList);
  out[118] = page;
  out[119] = last_page;
  for (std::size_t i = 0; i < universes.size(); ++i) put_u16_be(&out[kDiscoveryHeaderSize + 2 * i], universes[i]);
  return total;
}

std::optional<DiscoveryPacket> decode_discovery(std::span<const std::uint8_t> in, std::span<std::uint16_t> universes) noexcept {
  DiscoveryPacket p;
  if (!read_root_and_source(in, kDiscoveryHeaderSize, kVectorRootExtended, kVectorFramingDiscovery, p.cid, p.source_name) ||
      !flags_length_ok(in, kDiscoveryLayerAt) || get_u32_be(&in[114]) != kVectorDiscoveryList)
    return std::nullopt;
  const std::size_t list = in.size() - kDiscoveryHeaderSize;
  p.page = in[118];
  p.last_page = in[119];
  if ((list & 1U) != 0 || list / 2 > kMaxDiscoveryUniverses || p.page > p.last_page) return std::nullopt;
  p.universe_count = std::min(list / 2, universes.size());
  for (std::size_t i = 0; i < p.universe_count; ++i) universes[i] = get_u16_be(&in[kDiscoveryHeaderSize + 2 * i]);
  return p;
}

}  // namespace avar::firmware_iface::sacn
