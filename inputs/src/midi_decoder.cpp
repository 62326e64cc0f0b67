#include "avar/inputs/midi_decoder.hpp"

namespace avar::inputs {
namespace {

constexpr std::uint8_t kNoteOff = 0x80;
constexpr std::uint8_t kNoteOn = 0x90;
constexpr std::uint8_t kControlChange = 0xB0;
constexpr std::uint8_t kChannelPressure = 0xD0;
constexpr std::uint8_t kPitchBend = 0xE0;
constexpr std::uint8_t kFirstChannelModeController = 120;

/// Appends text to the name; the buffer fits every name this decoder makes.
void append(MidiControl* c, std::string_view text) noexcept {
  for (const char ch : text) c->name_buffer[c->name_length++] = ch;
}

void append(MidiControl* c, unsigned number) noexcept {
  char digits[3];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + number % 10);
    number /= 10;
  } while (number != 0 && n < 3);
  while (n > 0) c->name_buffer[c->name_length++] = digits[--n];
}

/// "ch<C>." with C 1..16.
void begin_name(MidiControl* c, unsigned channel_index) noexcept {
  c->name_length = 0;
  append(c, "ch");
  append(c, channel_index + 1);
  append(c, ".");
}

/// How many bytes a channel voice message of this status has, status included.
std::size_t voice_message_length(std::uint8_t status) noexcept {
  const std::uint8_t kind = status & 0xF0;
  return (kind == 0xC0 || kind == kChannelPressure) ? 2 : 3;
}

}  // namespace

bool MidiDecoder::decode(std::span<const std::uint8_t> message, MidiControl* control) noexcept {
  if (message.empty()) return false;
  const std::uint8_t status = message[0];
  if (status < 0x80 || status >= 0xF0) return false;  // running status, or a system message
  if (message.size() != voice_message_length(status)) return false;
  for (std::size_t i = 1; i < message.size(); ++i)
    if (message[i] >= 0x80) return false;

  const unsigned channel = status & 0x0F;
  const std::uint8_t d1 = message[1];
  const std::uint8_t d2 = message.size() > 2 ? message[2] : 0;
  MidiControl c;
  switch (status & 0xF0) {
    case kNoteOff:
    case kNoteOn:
      begin_name(&c, channel);
      append(&c, "note");
      append(&c, d1);
      c.value = (status & 0xF0) == kNoteOn ? d2 / 127.0 : 0.0;
      break;
    case kControlChange:
      if (d1 >= kFirstChannelModeController) return false;
      begin_name(&c, channel);
      append(&c, "cc");
      if (config_.fourteen_bit_cc && d1 < 32) {
        msb_[channel][d1] = d2;
        append(&c, d1);
        c.value = (d2 << 7) / 16383.0;
      } else if (config_.fourteen_bit_cc && d1 < 64) {
        append(&c, d1 - 32u);
        c.value = ((msb_[channel][d1 - 32] << 7) | d2) / 16383.0;
      } else {
        append(&c, d1);
        c.value = d2 / 127.0;
      }
      break;
    case kChannelPressure:
      begin_name(&c, channel);
      append(&c, "pressure");
      c.value = d1 / 127.0;
      break;
    case kPitchBend: {
      begin_name(&c, channel);
      append(&c, "bend");
      const int offset = ((d2 << 7) | d1) - 8192;  // -8192..8191
      c.value = offset < 0 ? offset / 8192.0 : offset / 8191.0;
      c.bipolar = true;
      break;
    }
    default:  // polyphonic key pressure, program change
      return false;
  }
  *control = c;
  return true;
}

}  // namespace avar::inputs
