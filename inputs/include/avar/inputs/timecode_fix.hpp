#pragma once
// What a timecode decoder learns from one message: which frame the source is at when the message
// arrived. Shared by the LTC, MTC and Art-Net decoders and the timecode sources.

#include <cstdint>

#include "avar/core/timecode.hpp"

namespace avar::inputs {

/// The two-bit rate code MTC (hours byte bits 5-6) and ArtTimeCode (Type) share: 0 = 24, 1 = 25,
/// 2 = 29.97 drop-frame, 3 = 30.
inline unsigned timecode_rate_code(FrameRate r) noexcept { return static_cast<unsigned>(r); }
inline FrameRate timecode_rate_from_code(unsigned code) noexcept { return static_cast<FrameRate>(code & 3U); }

struct TimecodeFix {
  Timecode label;  ///< the frame the message names
  /// Frames the source had moved past `label` when the message's last byte (or sample) arrived:
  /// 0 for Art-Net and MTC full frames, -0.25..1.5 for MTC quarter frames, ~1 for LTC (a frame's
  /// code ends as the next frame begins).
  double frames_after = 0;
  bool reverse = false;  ///< the source runs backwards (MTC direction, LTC played reversed)

  /// The source's position at arrival, seconds since 00:00:00:00.
  double seconds() const noexcept {
    return (static_cast<double>(to_frame_number(label)) + (reverse ? -frames_after : frames_after)) /
           frames_per_second(label.rate);
  }
};

}  // namespace avar::inputs
