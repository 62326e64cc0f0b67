#pragma once
// ArtPoll (OpCode 0x2000) and ArtPollReply (OpCode 0x2100) of Art-Net 4: a controller
// broadcasts ArtPoll, every node answers with one ArtPollReply per group of up to four ports.
//
// ArtPoll, after the versioned header: Flags, DiagPriority, TargetPortAddressTop (Hi, Lo),
// TargetPortAddressBottom (Hi, Lo), EstaMan (Hi, Lo), Oem (Hi, Lo): 22 bytes. Art-Net 3 nodes
// send only the first 14, which receivers must accept.
//
// ArtPollReply, 239 bytes, no protocol version after the OpCode: IP[4] at 10, Port (low byte
// first) at 14, VersInfo (Hi, Lo) at 16, NetSwitch 18, SubSwitch 19, Oem (Hi, Lo) 20, Ubea 22,
// Status1 23, EstaMan (Lo, Hi) 24, ShortName[18] 26, LongName[64] 44, NodeReport[64] 108,
// NumPorts (Hi, Lo) 172, PortTypes[4] 174, GoodInput[4] 178, GoodOutputA[4] 182, SwIn[4] 186,
// SwOut[4] 190, AcnPriority 194, SwMacro 195, SwRemote 196, spare[3], Style 200, MAC[6] 201,
// BindIp[4] 207, BindIndex 211, Status2 212, GoodOutputB[4] 213, Status3 217, then
// DefaultRespUID, User, RefreshRate and filler, written as zeros. Older nodes send replies cut
// after the MAC (207 bytes): decode accepts them, the missing fields read zero.
// Pure: no allocation, exception or I/O; real-time safe.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "avar/firmware_iface/artnet_header.hpp"

namespace avar::firmware_iface::artnet {

inline constexpr std::size_t kPollSize = 22;
inline constexpr std::size_t kMinPollSize = 14;
inline constexpr std::size_t kPollReplySize = 239;
inline constexpr std::size_t kMinPollReplySize = 207;
inline constexpr std::size_t kShortNameSize = 18;
inline constexpr std::size_t kLongNameSize = 64;
inline constexpr std::size_t kNodeReportSize = 64;

/// ArtPoll Flags bits.
enum PollFlags : std::uint8_t {
  kPollReplyOnChange = 0x02,  ///< send ArtPollReply whenever the node's conditions change
  kPollSendDiagnostics = 0x04,
  kPollUnicastDiagnostics = 0x08,
  kPollTargeted = 0x20,  ///< only nodes with a port in the target range reply
};

struct Poll {
  std::uint8_t flags = 0;
  std::uint8_t diag_priority = 0x10;  ///< DpLow
  std::uint16_t target_top = 0x7FFF;  ///< with target_bottom: the Port-Addresses a targeted poll asks for
  std::uint16_t target_bottom = 0;
  std::uint16_t esta_manufacturer = 0;
  std::uint16_t oem = 0;
};

/// A name field as written: the characters before the first NUL (at most size - 1 of them).
template <std::size_t N>
struct NameField {
  std::array<char, N> chars{};
  /// Copies at most N - 1 characters; the rest stays NUL.
  void set(std::string_view text) noexcept {
    chars.fill('\0');
    for (std::size_t i = 0; i < text.size() && i + 1 < N; ++i) chars[i] = text[i];
  }
  std::string_view view() const noexcept {
    std::size_t n = 0;
    while (n < N && chars[n] != '\0') ++n;
    return {chars.data(), n};
  }
};

struct PollReply {
  std::array<std::uint8_t, 4> ip{};
  std::uint16_t port = kUdpPort;
  std::uint16_t version_info = 0;  ///< the node's firmware revision
  std::uint8_t net_switch = 0;     ///< bits 14..8 of the Port-Address of every port
  std::uint8_t sub_switch = 0;     ///< bits 7..4
  std::uint16_t oem = 0;
  std::uint8_t ubea_version = 0;
  std::uint8_t status1 = 0;
  std::uint16_t esta_manufacturer = 0;
  NameField<kShortNameSize> short_name;
  NameField<kLongNameSize> long_name;
  NameField<kNodeReportSize> node_report;
  std::uint16_t num_ports = 0;               ///< 0..4
  std::array<std::uint8_t, 4> port_types{};  ///< bit 7 output, bit 6 input, bits 0..5 protocol (0 DMX512)
  std::array<std::uint8_t, 4> good_input{};
  std::array<std::uint8_t, 4> good_output_a{};
  std::array<std::uint8_t, 4> sw_in{};   ///< bits 3..0 of each input port's Port-Address
  std::array<std::uint8_t, 4> sw_out{};  ///< bits 3..0 of each output port's Port-Address
  std::uint8_t acn_priority = 0;
  std::uint8_t sw_macro = 0;
  std::uint8_t sw_remote = 0;
  std::uint8_t style = 0;  ///< 0 StNode, 1 StController ...
  std::array<std::uint8_t, 6> mac{};
  std::array<std::uint8_t, 4> bind_ip{};
  std::uint8_t bind_index = 0;
  std::uint8_t status2 = 0;
  std::array<std::uint8_t, 4> good_output_b{};
  std::uint8_t status3 = 0;

  /// The 15-bit Port-Address of output port `i` (0..3).
  std::uint16_t output_port_address(std::size_t i) const noexcept {
    return static_cast<std::uint16_t>(((net_switch & 0x7FU) << 8U) | ((sub_switch & 0x0FU) << 4U) | (sw_out[i] & 0x0FU));
  }
};

/// Writes the 22-byte ArtPoll; 0 when `out` is too small.
std::size_t encode_poll(std::span<std::uint8_t> out, const Poll& poll) noexcept;
/// Reads an ArtPoll of 14 bytes or more (fields a short one lacks keep their defaults, which
/// target every Port-Address); nullopt for anything else, shorter or of version below 14.
std::optional<Poll> decode_poll(std::span<const std::uint8_t> datagram) noexcept;

/// Writes the 239-byte ArtPollReply; 0 when `out` is too small or num_ports exceeds 4.
std::size_t encode_poll_reply(std::span<std::uint8_t> out, const PollReply& reply) noexcept;
/// Reads an ArtPollReply of at least 207 bytes; nullopt for anything else, shorter, or
/// claiming more than 4 ports.
std::optional<PollReply> decode_poll_reply(std::span<const std::uint8_t> datagram) noexcept;

}  // namespace avar::firmware_iface::artnet
