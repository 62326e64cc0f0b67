#include "avar/firmware_iface/ssc32_codec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace avar::firmware_iface::ssc32 {
namespace {

/// Appends text; false when out of room.
struct Writer {
  std::span<std::uint8_t> out;
  std::size_t n = 0;
  bool ok = true;
  void put(char c) {
    if (n >= out.size()) {
      ok = false;
      return;
    }
    out[n++] = static_cast<std::uint8_t>(c);
  }
  void number(std::uint32_t v) {
    char digits[10];
    const auto end = std::to_chars(digits, digits + sizeof digits, v).ptr;
    for (const char* p = digits; p != end; ++p) put(*p);
  }
  std::size_t finish() {
    put(static_cast<char>(kCr));
    return ok ? n : 0;
  }
};

/// One `<prefix><ch><suffix>` per channel, then CR.
std::size_t encode_per_channel(std::span<std::uint8_t> out, std::span<const std::uint8_t> channels, const char* prefix,
                               const char* suffix) noexcept {
  if (channels.empty() || channels.size() > kChannels) return 0;
  Writer w{out};
  for (std::uint8_t ch : channels) {
    if (ch >= kChannels) return 0;
    for (const char* p = prefix; *p; ++p) w.put(*p);
    w.number(ch);
    for (const char* p = suffix; *p; ++p) w.put(*p);
  }
  return w.finish();
}

bool is_space(std::uint8_t c) { return c == ' ' || c == '\t' || c == '\n'; }
bool is_digit(std::uint8_t c) { return c >= '0' && c <= '9'; }
std::uint8_t upper(std::uint8_t c) { return c >= 'a' && c <= 'z' ? static_cast<std::uint8_t>(c - 'a' + 'A') : c; }

/// Reads the line as tokens: runs of letters (upper-cased) and numbers (optionally signed).
class Tokens {
 public:
  explicit Tokens(std::span<const std::uint8_t> line) : line_(line) {}
  void skip_space() {
    while (at_ < line_.size() && is_space(line_[at_])) ++at_;
  }
  bool done() {
    skip_space();
    return at_ >= line_.size();
  }
  /// The next character (upper-cased) without taking it; 0 at the end.
  std::uint8_t peek() {
    skip_space();
    return at_ < line_.size() ? upper(line_[at_]) : 0;
  }
  /// Takes `word` if it comes next.
  bool take(const char* word) {
    skip_space();
    std::size_t i = at_;
    for (const char* w = word; *w; ++w, ++i)
      if (i >= line_.size() || upper(line_[i]) != static_cast<std::uint8_t>(*w)) return false;
    at_ = i;
    return true;
  }
  /// A decimal number, at most 6 digits.
  bool number(long& v, bool allow_sign = false) {
    skip_space();
    bool negative = false;
    if (allow_sign && at_ < line_.size() && (line_[at_] == '-' || line_[at_] == '+')) negative = line_[at_++] == '-';
    std::size_t digits = 0;
    v = 0;
    while (at_ < line_.size() && is_digit(line_[at_]) && digits < 7) v = v * 10 + (line_[at_++] - '0'), ++digits;
    if (negative) v = -v;
    return digits > 0 && digits < 7;
  }

 private:
  std::span<const std::uint8_t> line_;
  std::size_t at_ = 0;
};

}  // namespace

std::size_t encode_group_move(std::span<std::uint8_t> out, std::span<const ServoMove> moves, std::uint32_t time_ms) noexcept {
  if (moves.empty() || moves.size() > kChannels) return 0;
  Writer w{out};
  for (const ServoMove& m : moves) {
    if (m.channel >= kChannels) return 0;
    w.put('#');
    w.number(m.channel);
    w.put('P');
    w.number(std::clamp(m.pulse_us, kMinPulseUs, kMaxPulseUs));
    if (m.speed_us_per_s > 0) {
      w.put('S');
      w.number(m.speed_us_per_s);
    }
  }
  if (time_ms > 0) {
    w.put('T');
    w.number(std::min<std::uint32_t>(time_ms, 65535));
  }
  return w.finish();
}

std::size_t encode_outputs_low(std::span<std::uint8_t> out, std::span<const std::uint8_t> channels) noexcept {
  return encode_per_channel(out, channels, "#", "L");
}

std::size_t encode_query_pulse(std::span<std::uint8_t> out, std::span<const std::uint8_t> channels) noexcept {
  return encode_per_channel(out, channels, "QP", "");
}

std::size_t encode_query_movement(std::span<std::uint8_t> out) noexcept {
  Writer w{out};
  w.put('Q');
  return w.finish();
}

std::uint8_t reply_from_pulse(double pulse_us) noexcept {
  if (!(pulse_us > 0)) return 0;
  return static_cast<std::uint8_t>(std::clamp(std::lround(pulse_us / 10.0), 0L, 255L));
}

ParseResult parse_line(std::span<const std::uint8_t> line, Command* c) noexcept {
  *c = Command{};
  Tokens t(line);
  if (t.done()) return ParseResult::empty;
  long v = 0;
  if (t.peek() == 'Q') {
    if (t.take("QP")) {
      c->kind = Command::Kind::query_pulse;
      // "QP 5 QP 6" and "QP 5 6" both list channels.
      for (;;) {
        if (!t.number(v) || v >= kChannels || c->query_count >= kChannels) return ParseResult::invalid;
        c->query[c->query_count++] = static_cast<std::uint8_t>(v);
        if (t.done()) return ParseResult::ok;
        if (!t.take("QP") && !is_digit(t.peek())) return ParseResult::invalid;
      }
    }
    t.take("Q");
    c->kind = Command::Kind::query_movement;
    return t.done() ? ParseResult::ok : ParseResult::invalid;
  }
  bool first = true;
  while (!t.done()) {
    if (t.take("T")) {
      if (c->kind != Command::Kind::move || c->servo_count == 0 || !t.number(v) || v > 65535) return ParseResult::invalid;
      c->time_ms = static_cast<std::uint32_t>(v);
      return t.done() ? ParseResult::ok : ParseResult::invalid;
    }
    if (!t.take("#") || !t.number(v) || v >= kChannels || c->servo_count >= kChannels) return ParseResult::invalid;
    ServoMove& m = c->servos[c->servo_count];
    m.channel = static_cast<std::uint8_t>(v);
    Command::Kind kind;
    if (t.take("PO")) {
      kind = Command::Kind::offset;
      if (!t.number(v, true) || v < -100 || v > 100) return ParseResult::invalid;
      c->offsets[c->servo_count] = static_cast<std::int16_t>(v);
    } else if (t.take("P")) {
      kind = Command::Kind::move;
      if (!t.number(v) || v < kMinPulseUs || v > kMaxPulseUs) return ParseResult::invalid;
      m.pulse_us = static_cast<std::uint16_t>(v);
      if (t.take("S")) {
        if (!t.number(v) || v < 1 || v > 65535) return ParseResult::invalid;
        m.speed_us_per_s = static_cast<std::uint16_t>(v);
      }
    } else if (t.peek() == 'H' || t.peek() == 'L') {
      kind = Command::Kind::output;
      const bool high = t.take("H");
      if (!high) t.take("L");
      m.pulse_us = high ? 1 : 0;
    } else {
      return ParseResult::invalid;
    }
    if (!first && kind != c->kind) return ParseResult::invalid;  // kinds do not mix in one line
    c->kind = kind;
    first = false;
    ++c->servo_count;
  }
  return ParseResult::ok;
}

}  // namespace avar::firmware_iface::ssc32
