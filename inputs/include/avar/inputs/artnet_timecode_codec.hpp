#pragma once
// ArtTimeCode (Art-Net 4, OpCode 0x9700): 19 bytes, the versioned header, Filler1, StreamId,
// Frames, Seconds, Minutes, Hours, Type (0 film 24, 1 EBU 25, 2 DF 29.97, 3 SMPTE 30).
// Pure: no allocation, exception or I/O.

#include <cstddef>
#include <cstdint>
#include <span>

#include "avar/core/timecode.hpp"

namespace avar::inputs::artnet {

inline constexpr std::size_t kTimeCodeSize = 19;

/// Writes an ArtTimeCode for `t` (valid(t) expected; fields are written as given) into out.
/// Returns kTimeCodeSize, or 0 when out is too small.
std::size_t encode_timecode(const Timecode& t, std::uint8_t stream_id, std::span<std::uint8_t> out) noexcept;

enum class TimeCodeVerdict {
  ok,
  not_artnet,    ///< no Art-Net ID (or shorter than its header)
  other_opcode,  ///< Art-Net, another packet (ArtPoll, ArtDmx ...): not an error
  old_version,   ///< protocol version below 14
  too_short,     ///< an ArtTimeCode shorter than 19 bytes
  bad_type,      ///< Type above 3
  out_of_range,  ///< a field out of range for the rate (a dropped drop-frame label included)
};
const char* to_string(TimeCodeVerdict v) noexcept;

/// Decodes one UDP datagram; `t` is set when the verdict is ok. Extra trailing bytes are allowed
/// (later protocol revisions may add fields).
TimeCodeVerdict decode_timecode(std::span<const std::uint8_t> datagram, Timecode& t, std::uint8_t* stream_id = nullptr) noexcept;

}  // namespace avar::inputs::artnet
