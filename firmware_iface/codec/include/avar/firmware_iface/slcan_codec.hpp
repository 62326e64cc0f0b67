#pragma once
// SLCAN, the Lawicel ASCII CAN-over-serial protocol (../shared/protocols/slcan.md): pure
// encoders and decoders of single lines. No I/O, no clock, no allocation, no exception: every
// function is real-time safe. A "line" is the text before its terminating CR; encoders write the
// CR, decoders take the line without it. Hex digits are written upper case and read in either
// case.

#include <cstddef>
#include <cstdint>
#include <span>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface::slcan {

inline constexpr std::uint8_t kCr = 0x0D;   ///< ends every command and reply: OK
inline constexpr std::uint8_t kBel = 0x07;  ///< the adapter's "error" reply (not followed by CR)

/// The longest frame line with its CR: `T` + 8 id digits + DLC + 16 data digits + 4 timestamp
/// digits + CR (the Linux driver's `T1111222281122334455667788EA5F`).
inline constexpr std::size_t kMaxLineLength = 31;
/// Adapter timestamps roll over every minute: 0..59 999 ms.
inline constexpr std::uint16_t kTimestampModulo = 60'000;

/// The `Sn` code of a bitrate in bit/s: 0..8 for 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k,
/// 1M; -1 for any other rate (python-can's 750k "S7" and 83.3k "S9" are not accepted).
int bitrate_code(int bitrate) noexcept;
/// The bitrate in bit/s of an `Sn` code 0..8; 0 for any other code.
int bitrate_of_code(int code) noexcept;

/// Writes `frame` as a transmit command (`t`, `T`, `r` or `R`) followed by CR; returns its
/// length, or 0 when `out` is too small or the frame is invalid (can_frame_valid) or an error
/// frame. timestamp_ms >= 0 appends it as 4 hex digits (an adapter's received-frame line);
/// values are taken modulo kTimestampModulo.
std::size_t encode_frame(std::span<std::uint8_t> out, const CanFrame& frame, int timestamp_ms = -1) noexcept;

/// Writes the Linux-driver extension lines of an error frame (frame.error, its id CanErrorClass
/// bits): a state line `s` + letter + RX and TX error counters (3 decimal digits each) when
/// a state bit is set (bus-off `b`, else passive `p`, else warning `w`, else restarted `a`), then
/// an error line `e` + count + letters for the event bits (ack `a`, protocol `s` (stuff),
/// overrun `o`). Returns the total length (0, 1 or 2 lines), 0 also when `out` is too small.
std::size_t encode_error_lines(std::span<std::uint8_t> out, const CanFrame& frame, int rx_errors = 0, int tx_errors = 0) noexcept;

/// Writes `Sn` + CR for a bitrate; 0 when the rate has no code or `out` is too small.
std::size_t encode_bitrate_command(std::span<std::uint8_t> out, int bitrate) noexcept;

/// What one line from an adapter (or one command to it) is.
enum class LineKind : std::uint8_t {
  empty,        ///< a bare CR: OK
  frame,        ///< a data or remote frame (t, T, r, R), in Line::frame
  error_frame,  ///< a Linux state (s) or error (e) line, as an error frame in Line::frame
  ack,          ///< `z` or `Z`: a transmit acknowledged
  status,       ///< `Fxx`: status flags in Line::flags
  version,      ///< `V...` (any text after the letter)
  serial,       ///< `N...` (any text after the letter)
  malformed,    ///< anything else (noise, a truncated or over-long frame, bad hex)
};

struct Line {
  LineKind kind = LineKind::malformed;
  /// frame: id, format, rtr, dlc, data (timestamp left 0: the transport stamps it on its own
  /// clock). error_frame: error = true, id = CanErrorClass bits; a state line's counters in
  /// data[6] (TX) and data[7] (RX), clamped to 255, dlc 8 (the Linux error-frame layout).
  CanFrame frame;
  /// The adapter's millisecond timestamp when the frame line carried one (`Z1`), else -1.
  int timestamp_ms = -1;
  std::uint8_t flags = 0;  ///< status: the `F` reply's byte
};

/// Decodes one line (without its CR). A frame line with 4 more hex digits than its DLC needs
/// carries a timestamp; one is accepted whether or not timestamps were switched on, since some
/// adapters keep `Z1` across power cycles.
Line parse_line(std::span<const std::uint8_t> text) noexcept;

/// Lawicel status flags (`F` reply) as CanErrorClass bits: bit 0 RX FIFO full and bit 3 data
/// overrun -> overrun; bit 2 error warning -> warning; bit 5 error passive -> passive; bit 7 bus
/// error -> protocol. Bit 1 (TX FIFO full) and bit 6 (arbitration lost) are flow, not errors.
std::uint32_t error_classes_of_status(std::uint8_t flags) noexcept;
/// The Lawicel flags an adapter reports for CanErrorClass bits (the inverse of the above, with
/// bus-off shown as bus error + error passive, Lawicel having no bus-off bit).
std::uint8_t status_of_error_classes(std::uint32_t classes) noexcept;

/// Lawicel status flag bits.
enum StatusFlag : std::uint8_t {
  kRxFifoFull = 1u << 0,
  kTxFifoFull = 1u << 1,
  kErrorWarning = 1u << 2,
  kDataOverrun = 1u << 3,
  kErrorPassive = 1u << 5,
  kArbitrationLost = 1u << 6,
  kBusError = 1u << 7,
};

}  // namespace avar::firmware_iface::slcan
