#pragma once
// One classic CAN frame as every CAN transport, codec and simulated node passes it, and the bus
// arithmetic of the protocol notes: the worst-case bits a frame occupies on the wire (bit
// stuffing and the 3-bit inter-frame space included). Pure, real-time safe.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>

namespace avar::firmware_iface {

inline constexpr std::uint32_t kCanMaxStandardId = 0x7FF;
inline constexpr std::uint32_t kCanMaxExtendedId = 0x1FFFFFFF;
inline constexpr std::size_t kCanMaxData = 8;

/// Error classes of an error frame (CanFrame::error): in CanFrame::id, as bits.
enum CanErrorClass : std::uint32_t {
  kCanErrorProtocol = 1u << 0,   ///< a bit, stuff, form or CRC error seen on the bus
  kCanErrorAck = 1u << 1,        ///< a frame nobody acknowledged (no other node on the bus)
  kCanErrorWarning = 1u << 2,    ///< error counters passed the warning level (96)
  kCanErrorPassive = 1u << 3,    ///< error passive (counters >= 128)
  kCanErrorBusOff = 1u << 4,     ///< the controller left the bus (TX counter > 255)
  kCanErrorOverrun = 1u << 5,    ///< a receive or transmit buffer overflowed: frames lost
  kCanErrorRestarted = 1u << 6,  ///< the controller is back on the bus after bus-off
};

struct CanFrame {
  std::uint32_t id = 0;   ///< 11-bit (standard) or 29-bit (extended) identifier; error frames: CanErrorClass bits
  bool extended = false;  ///< 29-bit identifier
  bool rtr = false;       ///< remote transmission request: dlc given, no data
  bool error = false;     ///< an error frame reported by the controller (not sent on the wire)
  std::uint8_t dlc = 0;   ///< 0..8
  std::array<std::uint8_t, kCanMaxData> data{};
  /// Receive time on the transport's clock (FrameTransport::now()); 0 for frames to send.
  std::chrono::nanoseconds timestamp{0};

  std::span<const std::uint8_t> payload() const noexcept { return {data.data(), rtr ? 0u : dlc}; }
  bool operator==(const CanFrame& o) const noexcept;  ///< id, flags, dlc and payload (not the timestamp)
};

/// A data frame with `bytes` (at most 8; more are cut).
CanFrame can_data_frame(std::uint32_t id, std::span<const std::uint8_t> bytes, bool extended = false) noexcept;
/// A remote (RTR) frame asking for `dlc` bytes.
CanFrame can_remote_frame(std::uint32_t id, std::uint8_t dlc, bool extended = false) noexcept;
/// Whether id and dlc are in range for the frame's format (error frames are always valid).
bool can_frame_valid(const CanFrame& f) noexcept;

/// Worst-case bits a frame occupies on the bus: the stuffable part (start of frame to the end of
/// the CRC: 34 + 8n bits standard, 54 + 8n extended) gains a stuff bit for every 4 after the
/// first, then CRC delimiter, ACK, end of frame and the inter-frame space (13 bits). Matches the
/// notes: 8 data bytes 135 bits, 6 bytes 115, none 55 (standard). RTR frames carry no data bits.
constexpr int can_frame_bits(std::size_t data_bytes, bool extended = false) noexcept {
  const int stuffable = (extended ? 54 : 34) + 8 * static_cast<int>(data_bytes);
  return stuffable + (stuffable - 1) / 4 + 13;
}
inline int can_frame_bits(const CanFrame& f) noexcept { return can_frame_bits(f.rtr ? 0 : f.dlc, f.extended); }

/// The bitrates classic CAN controllers and SLCAN adapters are set to (bit/s): 10k, 20k, 50k,
/// 100k, 125k, 250k, 500k, 800k, 1M.
bool is_standard_can_bitrate(int bitrate) noexcept;

}  // namespace avar::firmware_iface
