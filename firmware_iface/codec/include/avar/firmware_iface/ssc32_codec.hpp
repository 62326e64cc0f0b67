#pragma once
// Lynxmotion SSC-32 / SSC-32U ASCII servo commands (../shared/protocols/ssc32.md): pure encoders,
// the line parser a device runs on every CR-terminated line, and the query replies. No I/O, no
// clock, no allocation, no exception: every function is real-time safe.
//
// Encoders write one command line (ending in CR) into `out` and return its length, or 0 when
// `out` is too small or an argument is invalid (a channel above 31, an empty group). Pulse
// widths saturate to 500..2500 µs, speeds to 1..65535 µs/s, times to 65535 ms.
//
// Query replies are raw bytes with no CR: QP answers one byte per queried channel, the pulse
// width / 10 (0 while the channel outputs no pulse); Q answers '.' (done) or '+' (moving).
// Several channels are queried as one line of repeated QP commands ("QP5QP6\r").

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace avar::firmware_iface::ssc32 {

inline constexpr int kChannels = 32;
inline constexpr std::uint16_t kMinPulseUs = 500;
inline constexpr std::uint16_t kMaxPulseUs = 2500;
inline constexpr std::uint8_t kCr = 0x0D;
inline constexpr std::uint8_t kEsc = 0x1B;
inline constexpr std::uint8_t kMoveDone = '.';
inline constexpr std::uint8_t kMoveInProgress = '+';
/// Longest line any encoder writes: 32 servos "#31P2500S65535" + "T65535" + CR.
inline constexpr std::size_t kMaxLineSize = 32 * 14 + 6 + 1;

struct ServoMove {
  std::uint8_t channel = 0;
  std::uint16_t pulse_us = 1500;
  std::uint16_t speed_us_per_s = 0;  ///< 0: no S (no per-servo speed limit)
};

/// `#<ch>P<pw>[S<spd>]...[T<time>]` CR. time_ms 0 leaves T out.
std::size_t encode_group_move(std::span<std::uint8_t> out, std::span<const ServoMove> moves, std::uint32_t time_ms) noexcept;
/// `#<ch>L...` CR: every listed channel's output held low (no more pulses: the servo goes limp).
std::size_t encode_outputs_low(std::span<std::uint8_t> out, std::span<const std::uint8_t> channels) noexcept;
/// `QP<ch>QP<ch>...` CR.
std::size_t encode_query_pulse(std::span<std::uint8_t> out, std::span<const std::uint8_t> channels) noexcept;
/// `Q` CR.
std::size_t encode_query_movement(std::span<std::uint8_t> out) noexcept;

/// Pulse width in µs of one QP reply byte (10 µs resolution); 0 = no pulse.
constexpr int pulse_from_reply(std::uint8_t byte) noexcept { return byte * 10; }
/// The QP reply byte for a pulse width (what the board answers).
std::uint8_t reply_from_pulse(double pulse_us) noexcept;

/// One command line as the board understands it.
struct Command {
  enum class Kind : std::uint8_t { move, offset, output, query_pulse, query_movement };
  Kind kind = Kind::move;
  /// move: channel, pulse and speed per servo; offset: channel per servo, the offset in
  /// offsets[]; output: channel per servo, pulse_us 0 (low) or 1 (high).
  std::array<ServoMove, kChannels> servos{};
  std::array<std::int16_t, kChannels> offsets{};
  std::size_t servo_count = 0;
  std::uint32_t time_ms = 0;                    ///< move: T, 0 when absent
  std::array<std::uint8_t, kChannels> query{};  ///< query_pulse: channels asked, in order
  std::size_t query_count = 0;
};

// clang-format 14 misreads an attribute on an enum and indents it:
// clang-format off
enum class [[nodiscard]] ParseResult {
  ok,
  empty,    ///< nothing but whitespace
  invalid,  ///< not a command the board accepts (unknown letters, mixed kinds, out of range): ignored
};
// clang-format on

/// Parses one line (without its CR) the way the board does: letters in either case, spaces,
/// tabs and line feeds separate but mean nothing, numbers in decimal (offsets may be negative).
/// Pulse widths outside 500..2500 are invalid (the line is ignored), as are channels above 31,
/// offsets outside ±100 and a T that is not the last item.
ParseResult parse_line(std::span<const std::uint8_t> line, Command* command) noexcept;

}  // namespace avar::firmware_iface::ssc32
