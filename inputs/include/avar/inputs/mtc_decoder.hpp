#pragma once
// MIDI Time Code (MIDI 1.0, MTC): quarter-frame messages (F1 0nnn dddd) assembled eight at a time
// over two frames, and full-frame SysEx (F0 7F <device> 01 01 hr mn sc fr F7).
//
// Quarter frames: piece n carries a nibble of frames (0, 1), seconds (2, 3), minutes (4, 5) or
// hours and rate (6, 7: bits 5-6 of the hours byte: 0 = 24, 1 = 25, 2 = 29.97 drop-frame, 3 = 30).
// The eight pieces describe the frame at which piece 0 was sent; by the time the last piece
// arrives the source is 1.75 frames later, and the next piece 0 starts frame + 2 (the "+2 frames"
// convention). Direction comes from the order the pieces arrive in (reverse: 7 down to 0). Once
// a sequence is complete every further quarter frame is a fix too (a quarter frame apart), so a
// chase gets four fixes per frame.
//
// Pure and real-time safe: no allocation, exception, I/O or clock. One thread per decoder.

#include <cstdint>
#include <optional>
#include <span>

#include "avar/inputs/timecode_fix.hpp"

namespace avar::inputs {

/// What became of one MIDI message.
enum class MtcVerdict {
  fix,           ///< a position (complete quarter-frame sequence, or a full frame)
  partial,       ///< a quarter frame taken, not yet a whole sequence
  not_timecode,  ///< a valid MIDI message of another kind (ignored, not an error)
  malformed,     ///< a quarter frame or full frame with bad bytes (out-of-range fields, bad length)
};

class MtcDecoder {
 public:
  /// Decodes one complete MIDI message (status byte first; SysEx with F0 and F7). `fix` is set
  /// when the verdict is MtcVerdict::fix.
  MtcVerdict decode(std::span<const std::uint8_t> message, TimecodeFix& fix) noexcept;

  /// Forgets any partial sequence (a port reopened, a long gap).
  void reset() noexcept;

 private:
  MtcVerdict quarter_frame(std::uint8_t data, TimecodeFix& fix) noexcept;

  std::uint8_t nibbles_[8] = {};
  std::uint8_t have_ = 0;  ///< bit n: piece n seen in the present run
  int last_piece_ = -1;
  int run_ = 0;  ///< pieces received in order, in the present direction
  bool reverse_ = false;
  bool locked_ = false;          ///< a whole sequence was assembled: pieces are fixes from here
  std::int64_t base_frame_ = 0;  ///< frame at which the present sequence's first piece was sent
  FrameRate rate_ = FrameRate::fps25;
};

}  // namespace avar::inputs
