#include "avar/firmware_iface/slcan_codec.hpp"

#include <algorithm>
#include <array>

namespace avar::firmware_iface::slcan {
namespace {

constexpr std::array<int, 9> kBitrates{10'000, 20'000, 50'000, 100'000, 125'000, 250'000, 500'000, 800'000, 1'000'000};
constexpr char kHexDigits[] = "0123456789ABCDEF";

/// The value of one hex digit (either case), or -1.
int hex_value(std::uint8_t c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// Reads `digits` hex digits at text[at...]; false when one is not hex.
bool read_hex(std::span<const std::uint8_t> text, std::size_t at, std::size_t digits, std::uint32_t* value) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < digits; ++i) {
    const int d = hex_value(text[at + i]);
    if (d < 0) return false;
    v = (v << 4) | static_cast<std::uint32_t>(d);
  }
  *value = v;
  return true;
}

bool read_decimal(std::span<const std::uint8_t> text, std::size_t at, std::size_t digits, std::uint32_t* value) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < digits; ++i) {
    const std::uint8_t c = text[at + i];
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  *value = v;
  return true;
}

/// Appends characters to a fixed buffer; remembers when it ran out of room.
struct Writer {
  std::span<std::uint8_t> out;
  std::size_t size = 0;
  bool overflow = false;

  void put(std::uint8_t c) noexcept {
    if (size < out.size()) out[size++] = c;
    else overflow = true;
  }
  void hex(std::uint32_t value, int digits) noexcept {
    for (int i = digits - 1; i >= 0; --i) put(static_cast<std::uint8_t>(kHexDigits[(value >> (4 * i)) & 0xF]));
  }
  void decimal(int value, int digits) noexcept {
    int divisor = 1;
    for (int i = 1; i < digits; ++i) divisor *= 10;
    for (; divisor > 0; divisor /= 10) put(static_cast<std::uint8_t>('0' + (value / divisor) % 10));
  }
};

Line parse_frame(std::span<const std::uint8_t> text) noexcept {
  Line line;
  const std::uint8_t letter = text[0];
  CanFrame& f = line.frame;
  f.extended = letter == 'T' || letter == 'R';
  f.rtr = letter == 'r' || letter == 'R';
  const std::size_t id_digits = f.extended ? 8 : 3;
  if (text.size() < 1 + id_digits + 1) return line;
  std::uint32_t id = 0;
  if (!read_hex(text, 1, id_digits, &id) || id > (f.extended ? kCanMaxExtendedId : kCanMaxStandardId)) return line;
  const std::uint8_t dlc = text[1 + id_digits];
  if (dlc < '0' || dlc > '8') return line;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(dlc - '0');
  const std::size_t data_at = 2 + id_digits;
  const std::size_t data_digits = f.rtr ? 0 : 2u * f.dlc;
  const std::size_t end = data_at + data_digits;
  if (text.size() != end && text.size() != end + 4) return line;
  for (std::size_t i = 0; i < data_digits / 2; ++i) {
    std::uint32_t byte = 0;
    if (!read_hex(text, data_at + 2 * i, 2, &byte)) return line;
    f.data[i] = static_cast<std::uint8_t>(byte);
  }
  if (text.size() == end + 4) {
    std::uint32_t ms = 0;
    if (!read_hex(text, end, 4, &ms)) return line;
    line.timestamp_ms = static_cast<int>(ms);
  }
  line.kind = LineKind::frame;
  return line;
}

/// `s` + state letter + RX and TX counters (3 decimal digits each).
Line parse_state(std::span<const std::uint8_t> text) noexcept {
  Line line;
  std::uint32_t rx = 0, tx = 0;
  if (text.size() != 8 || !read_decimal(text, 2, 3, &rx) || !read_decimal(text, 5, 3, &tx)) return line;
  std::uint32_t classes = 0;
  switch (text[1]) {
    case 'a': break;  // back to error active: no error class remains
    case 'w': classes = kCanErrorWarning; break;
    case 'p': classes = kCanErrorPassive; break;
    case 'b': classes = kCanErrorBusOff; break;
    default: return line;
  }
  line.kind = LineKind::error_frame;
  line.frame.error = true;
  line.frame.id = classes;
  line.frame.dlc = 8;
  line.frame.data[6] = static_cast<std::uint8_t>(std::min<std::uint32_t>(tx, 255));
  line.frame.data[7] = static_cast<std::uint8_t>(std::min<std::uint32_t>(rx, 255));
  return line;
}

/// `e` + count digit + that many error letters.
Line parse_errors(std::span<const std::uint8_t> text) noexcept {
  Line line;
  if (text.size() < 3 || text[1] < '1' || text[1] > '9' || text.size() != 2u + (text[1] - '0')) return line;
  std::uint32_t classes = 0;
  for (std::size_t i = 2; i < text.size(); ++i) {
    switch (text[i]) {
      case 'a': classes |= kCanErrorAck; break;
      case 'b':
      case 'B':
      case 'c':
      case 'f':
      case 's': classes |= kCanErrorProtocol; break;
      case 'o':
      case 'O': classes |= kCanErrorOverrun; break;
      default: return line;
    }
  }
  line.kind = LineKind::error_frame;
  line.frame.error = true;
  line.frame.id = classes;
  return line;
}

}  // namespace

int bitrate_code(int bitrate) noexcept {
  for (std::size_t i = 0; i < kBitrates.size(); ++i)
    if (kBitrates[i] == bitrate) return static_cast<int>(i);
  return -1;
}

int bitrate_of_code(int code) noexcept {
  return code >= 0 && code < static_cast<int>(kBitrates.size()) ? kBitrates[static_cast<std::size_t>(code)] : 0;
}

std::size_t encode_frame(std::span<std::uint8_t> out, const CanFrame& frame, int timestamp_ms) noexcept {
  if (frame.error || !can_frame_valid(frame)) return 0;
  Writer w{out};
  w.put(frame.rtr ? (frame.extended ? 'R' : 'r') : (frame.extended ? 'T' : 't'));
  w.hex(frame.id, frame.extended ? 8 : 3);
  w.put(static_cast<std::uint8_t>('0' + frame.dlc));
  for (std::uint8_t b : frame.payload()) w.hex(b, 2);
  if (timestamp_ms >= 0) w.hex(static_cast<std::uint32_t>(timestamp_ms % kTimestampModulo), 4);
  w.put(kCr);
  return w.overflow ? 0 : w.size;
}

std::size_t encode_error_lines(std::span<std::uint8_t> out, const CanFrame& frame, int rx_errors, int tx_errors) noexcept {
  if (!frame.error) return 0;
  Writer w{out};
  const std::uint32_t c = frame.id;
  if (c & (kCanErrorBusOff | kCanErrorPassive | kCanErrorWarning | kCanErrorRestarted)) {
    w.put('s');
    w.put((c & kCanErrorBusOff) ? 'b' : (c & kCanErrorPassive) ? 'p' : (c & kCanErrorWarning) ? 'w' : 'a');
    w.decimal(std::clamp(rx_errors, 0, 999), 3);
    w.decimal(std::clamp(tx_errors, 0, 999), 3);
    w.put(kCr);
  }
  std::array<std::uint8_t, 3> letters{};
  std::size_t count = 0;
  if (c & kCanErrorAck) letters[count++] = 'a';
  if (c & kCanErrorProtocol) letters[count++] = 's';
  if (c & kCanErrorOverrun) letters[count++] = 'o';
  if (count > 0) {
    w.put('e');
    w.put(static_cast<std::uint8_t>('0' + count));
    for (std::size_t i = 0; i < count; ++i) w.put(letters[i]);
    w.put(kCr);
  }
  return w.overflow ? 0 : w.size;
}

std::size_t encode_bitrate_command(std::span<std::uint8_t> out, int bitrate) noexcept {
  const int code = bitrate_code(bitrate);
  if (code < 0 || out.size() < 3) return 0;
  out[0] = 'S';
  out[1] = static_cast<std::uint8_t>('0' + code);
  out[2] = kCr;
  return 3;
}

Line parse_line(std::span<const std::uint8_t> text) noexcept {
  Line line;
  if (text.empty()) {
    line.kind = LineKind::empty;
    return line;
  }
  switch (text[0]) {
    case 't':
    case 'T':
    case 'r':
    case 'R': return parse_frame(text);
    case 's': return parse_state(text);
    case 'e': return parse_errors(text);
    case 'z':
    case 'Z':
      if (text.size() == 1) line.kind = LineKind::ack;
      return line;
    case 'F': {
      std::uint32_t flags = 0;
      if (text.size() == 3 && read_hex(text, 1, 2, &flags)) {
        line.kind = LineKind::status;
        line.flags = static_cast<std::uint8_t>(flags);
      }
      return line;
    }
    case 'V':
    case 'v': line.kind = LineKind::version; return line;
    case 'N': line.kind = LineKind::serial; return line;
    default: return line;
  }
}

std::uint32_t error_classes_of_status(std::uint8_t flags) noexcept {
  std::uint32_t classes = 0;
  if (flags & (kRxFifoFull | kDataOverrun)) classes |= kCanErrorOverrun;
  if (flags & kErrorWarning) classes |= kCanErrorWarning;
  if (flags & kErrorPassive) classes |= kCanErrorPassive;
  if (flags & kBusError) classes |= kCanErrorProtocol;
  return classes;
}

std::uint8_t status_of_error_classes(std::uint32_t classes) noexcept {
  std::uint8_t flags = 0;
  if (classes & kCanErrorOverrun) flags |= kDataOverrun;
  if (classes & kCanErrorWarning) flags |= kErrorWarning;
  if (classes & (kCanErrorPassive | kCanErrorBusOff)) flags |= kErrorPassive;
  if (classes & (kCanErrorProtocol | kCanErrorBusOff)) flags |= kBusError;
  return flags;
}

}  // namespace avar::firmware_iface::slcan
