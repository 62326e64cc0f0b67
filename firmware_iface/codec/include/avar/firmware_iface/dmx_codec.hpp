#pragma once
// ENTTEC DMX USB Pro widget messages (../shared/protocols/enttec-dmx-usb-pro.md): pure encoders
// and a resynchronising decoder. No I/O, no clock, no allocation, no exception: real-time safe.
//
// Every message, both directions: 7E LABEL LEN_LSB LEN_MSB DATA... E7 (LEN = data bytes, at
// most 600; no checksum). Encoders return the message length, or 0 when `out` is too small or
// an argument is invalid.

#include <cstddef>
#include <cstdint>
#include <span>

namespace avar::firmware_iface::dmx {

inline constexpr std::uint8_t kStartOfMessage = 0x7E;
inline constexpr std::uint8_t kEndOfMessage = 0xE7;
inline constexpr std::size_t kMaxData = 600;
inline constexpr std::size_t kOverhead = 5;  ///< 7E, label, 2 length bytes, E7
inline constexpr std::size_t kMaxMessageSize = kMaxData + kOverhead;
inline constexpr std::size_t kUniverseSize = 512;
inline constexpr std::size_t kMinSlots = 24;  ///< shorter universes are padded with zeros
inline constexpr std::uint8_t kDimmerStartCode = 0x00;

enum Label : std::uint8_t {
  kGetWidgetParameters = 3,
  kSetWidgetParameters = 4,
  kReceivedDmx = 5,
  kOutputOnlySendDmx = 6,
  kGetSerialNumber = 10,
};

/// The widget's DMX output timing (labels 3 and 4).
struct WidgetParameters {
  std::uint16_t firmware = 0;     ///< reply only
  std::uint8_t break_time = 9;    ///< units of 10.67 µs, 9..127
  std::uint8_t mab_time = 1;      ///< units of 10.67 µs, 1..127
  std::uint8_t output_rate = 40;  ///< packets per second 1..40, 0 = as fast as possible
};

std::size_t encode_message(std::span<std::uint8_t> out, std::uint8_t label, std::span<const std::uint8_t> data) noexcept;
/// Label 6: the start code then the slots (channel 1 first), padded with zeros to 24 slots.
/// At most 512 slots.
std::size_t encode_send_dmx(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots,
                            std::uint8_t start_code = kDimmerStartCode) noexcept;
/// Label 3 request, asking for `user_config_size` bytes of user configuration (0..508).
std::size_t encode_get_widget_parameters(std::span<std::uint8_t> out, std::uint16_t user_config_size = 0) noexcept;
/// Label 4, no user configuration. Refuses values outside the ranges above.
std::size_t encode_set_widget_parameters(std::span<std::uint8_t> out, const WidgetParameters& p) noexcept;
/// Label 10 request.
std::size_t encode_get_serial_number(std::span<std::uint8_t> out) noexcept;
/// The widget's label 3 reply (firmware LSB, MSB, break, MAB, rate, user configuration).
std::size_t encode_widget_parameters_reply(std::span<std::uint8_t> out, const WidgetParameters& p,
                                           std::span<const std::uint8_t> user_config) noexcept;

/// Bytes of a label 6 message for `slots` slots (padding included).
constexpr std::size_t send_dmx_size(std::size_t slots) noexcept {
  return kOverhead + 1 + (slots < kMinSlots ? kMinSlots : slots);
}
/// Seconds one DMX512 packet of `slots` slots takes on the DMX line (break 92 µs, MAB 12 µs,
/// 44 µs per slot incl. the start code, at least 1204 µs break to break).
constexpr double dmx_packet_seconds(std::size_t slots) noexcept {
  const double t = 92e-6 + 12e-6 + 44e-6 * static_cast<double>(1 + (slots < kMinSlots ? kMinSlots : slots));
  return t < 1204e-6 ? 1204e-6 : t;
}

struct Message {
  std::uint8_t label = 0;
  std::span<const std::uint8_t> data;  ///< points into the input
};

// clang-format 14 misreads an attribute on an enum and indents it:
// clang-format off
enum class [[nodiscard]] DecodeResult {
  ok,
  need_more,    ///< a message may have started but is not complete
  bad_framing,  ///< no 7E, a length above 600 or no E7 where it belongs: drop *consumed bytes
};
// clang-format on

/// Looks for one message at the start of `in`; *consumed: the message (ok) or the bytes to drop.
DecodeResult decode_message(std::span<const std::uint8_t> in, Message* message, std::size_t* consumed) noexcept;
/// Reads a label 3 reply's data; false when it is shorter than 5 bytes.
bool decode_widget_parameters(std::span<const std::uint8_t> data, WidgetParameters* p) noexcept;

}  // namespace avar::firmware_iface::dmx
