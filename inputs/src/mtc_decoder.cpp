#include "avar/inputs/mtc_decoder.hpp"

namespace avar::inputs {
namespace {

constexpr std::uint8_t kQuarterFrame = 0xF1;
constexpr std::size_t kFullFrameSize = 10;

/// The nibble piece `piece` carries for label `t`.
std::uint8_t mtc_nibble(const Timecode& t, int piece) noexcept {
  const auto low = [](int v) { return static_cast<std::uint8_t>(static_cast<unsigned>(v) & 0xFU); };
  const auto high = [](int v) { return static_cast<std::uint8_t>(static_cast<unsigned>(v) >> 4U); };
  switch (piece) {
    case 0: return low(t.frames);
    case 1: return high(t.frames);
    case 2: return low(t.seconds);
    case 3: return high(t.seconds);
    case 4: return low(t.minutes);
    case 5: return high(t.minutes);
    case 6: return low(t.hours);
    default: return static_cast<std::uint8_t>(high(t.hours) | (timecode_rate_code(t.rate) << 1U));
  }
}

}  // namespace

void MtcDecoder::reset() noexcept {
  have_ = 0;
  last_piece_ = -1;
  run_ = 0;
  locked_ = false;
}

MtcVerdict MtcDecoder::decode(std::span<const std::uint8_t> message, TimecodeFix& fix) noexcept {
  if (message.empty()) return MtcVerdict::malformed;
  if (message[0] == kQuarterFrame) {
    if (message.size() != 2 || message[1] > 0x7F) return MtcVerdict::malformed;
    return quarter_frame(message[1], fix);
  }
  // Full frame: F0 7F <device> 01 01 hr mn sc fr F7.
  const bool full_frame =
      message.size() >= 5 && message[0] == 0xF0 && message[1] == 0x7F && message[3] == 0x01 && message[4] == 0x01;
  if (!full_frame) return MtcVerdict::not_timecode;
  if (message.size() != kFullFrameSize || message[9] != 0xF7) return MtcVerdict::malformed;
  for (std::size_t i = 5; i < 9; ++i)
    if (message[i] > 0x7F) return MtcVerdict::malformed;
  const Timecode t{message[5] & 0x1F, message[6], message[7], message[8],
                   timecode_rate_from_code(static_cast<unsigned>(message[5]) >> 5U)};
  if (!valid(t)) return MtcVerdict::malformed;
  reset();  // a locate: quarter frames start over from here
  fix = TimecodeFix{t, 0.0, false};
  return MtcVerdict::fix;
}

MtcVerdict MtcDecoder::quarter_frame(std::uint8_t data, TimecodeFix& fix) noexcept {
  const auto piece = static_cast<int>((data >> 4U) & 7U);
  const auto nibble = static_cast<std::uint8_t>(data & 0xFU);
  const bool forward_next = last_piece_ >= 0 && piece == (last_piece_ + 1) % 8;
  const bool reverse_next = last_piece_ >= 0 && piece == (last_piece_ + 7) % 8;
  if ((forward_next && !reverse_) || (reverse_next && reverse_)) {
    ++run_;
  } else if (forward_next || reverse_next) {
    // The direction changed: start a new run that way.
    reverse_ = reverse_next;
    run_ = 2;
    locked_ = false;
  } else {
    run_ = 1;
    locked_ = false;
  }
  last_piece_ = piece;
  nibbles_[piece] = nibble;
  const int final_piece = reverse_ ? 0 : 7;
  const double step = reverse_ ? -2.0 : 2.0;

  if (locked_ && nibble != mtc_nibble(from_frame_number(base_frame_, rate_), piece)) locked_ = false;  // a jump
  if (piece != final_piece) {
    if (!locked_) return MtcVerdict::partial;
    // A quarter frame of a sequence that continues the last one: its position is known now.
    const double quarters = reverse_ ? 7 - piece : piece;
    fix = TimecodeFix{from_frame_number(base_frame_, rate_), quarters / 4.0, reverse_};
    return MtcVerdict::fix;
  }
  if (run_ < 8) return MtcVerdict::partial;
  const Timecode t{(nibbles_[6] & 0xF) | ((nibbles_[7] & 1) << 4), (nibbles_[4] & 0xF) | ((nibbles_[5] & 3) << 4),
                   (nibbles_[2] & 0xF) | ((nibbles_[3] & 3) << 4), (nibbles_[0] & 0xF) | ((nibbles_[1] & 1) << 4),
                   timecode_rate_from_code(static_cast<unsigned>(nibbles_[7]) >> 1U)};
  if (!valid(t)) {
    locked_ = false;
    return MtcVerdict::malformed;
  }
  // The sequence named the frame at which its first piece was sent; the next sequence starts two
  // frames on (the "+2" convention), a quarter frame after this last piece.
  rate_ = t.rate;
  base_frame_ = to_frame_number(t) + static_cast<std::int64_t>(step);
  locked_ = true;
  fix = TimecodeFix{from_frame_number(base_frame_, rate_), -0.25, reverse_};
  return MtcVerdict::fix;
}

}  // namespace avar::inputs
