#pragma once
// ANSI E1.31 (streaming ACN, "sACN"): the data packet carrying one DMX512 universe and the
// universe discovery packet. All multi-byte fields are big-endian. Every PDU starts with 16 bits
// of flags (0x7 in the top nibble) and length (the PDU's bytes from its flags on, 12 bits).
//
// Data packet (126 + slots bytes): root layer: preamble size 0x0010, post-amble size 0, ACN
// packet identifier "ASC-E1.17\0\0\0", flags+length at 16, vector 0x00000004 (E131_DATA), CID[16]
// at 22; framing layer at 38: flags+length, vector 0x00000002 (E131_DATA_PACKET), source name[64]
// (UTF-8, NUL-terminated) at 44, priority (0..200) at 108, synchronization address at 109,
// sequence number at 111, options at 112 (0x80 preview data, 0x40 stream terminated, 0x20 force
// synchronization), universe (1..63999) at 113; DMP layer at 115: flags+length, vector 0x02
// (SET_PROPERTY), address and data type 0xA1, first property address 0, address increment 1,
// property value count (1 + slots), then the start code and the slots.
//
// Universe discovery packet (120 + 2 per universe): root vector 0x00000008 (E131_EXTENDED);
// framing layer at 38: flags+length, vector 0x00000002 (E131_EXTENDED_DISCOVERY), source name[64],
// 4 reserved bytes; discovery layer at 112: flags+length, vector 0x00000001 (UNIVERSE_LIST), page,
// last page, then up to 512 universes in ascending order. Sent to universe 64214.
// Pure: no allocation, exception or I/O; real-time safe.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace avar::firmware_iface::sacn {

inline constexpr std::uint16_t kUdpPort = 5568;
inline constexpr std::uint16_t kMinUniverse = 1;
inline constexpr std::uint16_t kMaxUniverse = 63999;
inline constexpr std::uint16_t kDiscoveryUniverse = 64214;
inline constexpr std::uint8_t kMaxPriority = 200;
inline constexpr std::uint8_t kDefaultPriority = 100;
inline constexpr std::size_t kSourceNameSize = 64;
inline constexpr std::size_t kDataHeaderSize = 125;  ///< everything before the start code
inline constexpr std::size_t kMaxSlots = 512;
inline constexpr std::size_t kMaxDataPacketSize = kDataHeaderSize + 1 + kMaxSlots;
inline constexpr std::size_t kDiscoveryHeaderSize = 120;
inline constexpr std::size_t kMaxDiscoveryUniverses = 512;
inline constexpr std::size_t kMaxDiscoveryPacketSize = kDiscoveryHeaderSize + 2 * kMaxDiscoveryUniverses;
/// Seconds between universe discovery packets (E131_UNIVERSE_DISCOVERY_INTERVAL).
inline constexpr double kDiscoveryIntervalS = 10.0;

enum Options : std::uint8_t {
  kPreviewData = 0x80,
  kStreamTerminated = 0x40,
  kForceSynchronization = 0x20,
};

/// Component identifier: a UUID naming the source for its lifetime.
using Cid = std::array<std::uint8_t, 16>;

/// What identifies a source in every packet it sends.
struct Source {
  Cid cid{};
  std::string_view name;  ///< at most 63 bytes are sent
};

struct DataHeader {
  std::uint16_t universe = 1;
  std::uint8_t priority = kDefaultPriority;
  std::uint16_t sync_address = 0;  ///< 0: not synchronized
  std::uint8_t sequence = 0;
  std::uint8_t options = 0;  ///< Options bits
  std::uint8_t start_code = 0;
};

struct DataPacket {
  Cid cid{};
  std::string_view source_name;  ///< points into the datagram
  DataHeader header;
  std::span<const std::uint8_t> slots;  ///< points into the datagram; 0..512 slots
};

struct DiscoveryPacket {
  Cid cid{};
  std::string_view source_name;
  std::uint8_t page = 0;
  std::uint8_t last_page = 0;
  std::size_t universe_count = 0;  ///< universes copied out
};

/// 239.255.hi.lo, in host byte order, for universe 1..63999 (and the discovery universe).
constexpr std::uint32_t multicast_group(std::uint16_t universe) noexcept { return 0xEFFF0000U | universe; }

/// Bytes of a data packet carrying `slots` slots.
constexpr std::size_t data_packet_size(std::size_t slots) noexcept { return kDataHeaderSize + 1 + slots; }

/// Writes a data packet; 0 when `out` is too small, slots exceed 512, the universe is outside
/// 1..63999 or the priority above 200.
std::size_t encode_data(std::span<std::uint8_t> out, const Source& source, const DataHeader& header,
                        std::span<const std::uint8_t> slots) noexcept;
/// Reads a data packet; nullopt for anything malformed: a wrong preamble, identifier, vector,
/// flags or length at any layer, a length disagreeing with the datagram, a source name without
/// NUL, a priority above 200, a universe outside 1..63999, a DMP layer other than 0xA1 from
/// address 0 by 1, a property count of 0 or above 513.
std::optional<DataPacket> decode_data(std::span<const std::uint8_t> in) noexcept;

/// Writes one page of universe discovery; 0 when `out` is too small, more than 512 universes, a
/// list not strictly ascending, or page after last_page.
std::size_t encode_discovery(std::span<std::uint8_t> out, const Source& source, std::uint8_t page, std::uint8_t last_page,
                             std::span<const std::uint16_t> universes) noexcept;
/// Reads a universe discovery packet, copying its universes into `universes` (at most its size);
/// nullopt for anything malformed (as decode_data, plus an odd list length, page after last
/// page, more than 512 universes).
std::optional<DiscoveryPacket> decode_discovery(std::span<const std::uint8_t> in, std::span<std::uint16_t> universes) noexcept;

}  // namespace avar::firmware_iface::sacn
