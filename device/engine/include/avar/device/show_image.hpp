#pragma once
// The device show image: a show's curves as bytes for flash, read in place (PROGMEM on AVR).
// Written by the host's exporter (avar/device/show_export.hpp), read by the device engine; the
// format is the contract between them and is documented in docs/reference/device-show-image.md.
//
// Values are in output units: 0..65535 over the channel's range (rig min to max), stored as
// integers that may lie outside it (a handle, an overshoot); the engine saturates what it outputs.
// Times are integer ticks of the image's ticks_per_second, signed (a curve may start before 0).
// Multi-byte fields are little-endian; "varint" is unsigned LEB128 and "zigzag" maps a signed
// number n to 2n (n >= 0) or -2n - 1 (n < 0) before the varint, as protocol buffers do.
//
// Image:
//   0  "avd1"                magic
//   4  u8   format version (kFormatVersion)
//   5  u8   channel count (1..kMaxChannels)
//   6  u8   flags: bit 0 the show loops
//   7  u8   snap ticks: a tick within this many ticks of a key is the key (avar's key snap)
//   8  u32  ticks per second
//   12 i32  duration in ticks (the loop point)
//   16 u32  offset of each channel's record from the image start, one per channel
// Channel record:
//   u8  flags: bit 0 linear extrapolation, bit 1 cycles
//   u16 key count (at least 1)
//   linear extrapolation: zigzag slope before, zigzag slope after (Q8 output units per second)
//   cycles: u8 modes (before: low nibble, after: high nibble; CycleMode), varint before count,
//           varint after count (0: forever), zigzag last - first key value (Q8 output units)
//   the keys
// Key (the segment that starts at it follows its time and value):
//   u8  kind (bits 0..4, SegmentKind), easing (bits 5..6, EasingMode); a Bezier key has no easing:
//       bit 5 says its handle times are the channel's previous Bezier key's (and are not stored),
//       bit 7 that they are wide
//   time: the first key's as a zigzag tick, the others' as a varint of ticks after the previous key
//   value: zigzag change from the previous key's value (the first key's from 0)
//   what the segment needs:
//     step, linear, the last key: nothing
//     cubic: zigzag first inner control point - this key's value, zigzag second inner control
//            point - the next key's value (the value cubic in Bernstein form, time linear)
//     bezier: as cubic, then (without bit 5) the handles' times as fractions of the segment, at
//             most 1: u16 each (Q15), or with bit 7 u24 each (Q23)
//     back: zigzag overshoot (Q16)
//     elastic: u8 1 when blended (Blender's amplitude 0 or below |change|), then zigzag the blend's
//              factor (Q30) or the wave's amplitude (Q8 output units), varint period (Q30 of the
//              segment's duration, Blender's default resolved), zigzag Blender's shift s (Q30 of
//              the duration)
//     the other easing families: nothing

#include <stddef.h>
#include <stdint.h>

#include "avar/device/config.hpp"

namespace avar {
namespace device {

const uint8_t kFormatVersion = 1;
const uint8_t kMaxChannels = 64;
const uint32_t kHeaderSize = 16;

enum SegmentKind : uint8_t {
  kStep = 0,
  kLinear = 1,
  kCubic = 2,
  kBezier = 3,
  kSine = 4,
  kQuad = 5,
  kCubicEase = 6,
  kQuart = 7,
  kQuint = 8,
  kExpo = 9,
  kCirc = 10,
  kBack = 11,
  kBounce = 12,
  kElastic = 13,
  kKindCount = 14,
};
enum EasingMode : uint8_t { kEaseIn = 0, kEaseOut = 1, kEaseInOut = 2 };
enum CycleMode : uint8_t { kCycleNone = 0, kCycleRepeat = 1, kCycleRepeatOffset = 2, kCycleMirror = 3 };

const uint8_t kChannelLinearExtrapolation = 1;
const uint8_t kChannelCycles = 2;
const uint8_t kShowLoops = 1;
const uint8_t kKeyWideBezier = 0x80;
const uint8_t kKeySameHandleTimes = 0x20;  ///< a Bezier key: its handle times are the last Bezier key's

/// Reads an image sequentially; past the end (a bad image) it reads zeros and remembers it.
struct ByteReader {
  const uint8_t* image;
  uint32_t size;
  uint32_t at;
  bool overrun;

  uint8_t u8() {
    if (at >= size) {
      overrun = true;
      return 0;
    }
    return AVAR_DEVICE_READ_BYTE(image + at++);
  }
  uint32_t fixed(unsigned bytes) {
    uint32_t v = 0;
    for (unsigned i = 0; i < bytes; ++i) v |= static_cast<uint32_t>(u8()) << (8 * i);
    return v;
  }
  /// Unsigned LEB128 of at most 10 bytes.
  uint64_t varint() {
    uint64_t v = 0;
    for (unsigned shift = 0; shift < 70; shift += 7) {
      const uint8_t b = u8();
      if (shift < 64) v |= static_cast<uint64_t>(b & 0x7fu) << shift;
      if (!(b & 0x80u)) return v;
    }
    overrun = true;
    return 0;
  }
  int64_t zigzag() {
    const uint64_t v = varint();
    return (v & 1u) ? -static_cast<int64_t>(v >> 1) - 1 : static_cast<int64_t>(v >> 1);
  }
};

/// What an image asks of the engine beyond steps, lines and cubics (config.hpp's switches).
const uint8_t kFeatureEasings = 1;
const uint8_t kFeatureCycles = 2;
const uint8_t kFeatureExtrapolation = 4;

/// The header of an image, read and checked.
struct ShowHeader {
  uint8_t channel_count;
  uint8_t flags;
  uint8_t snap_ticks;
  uint32_t ticks_per_second;
  int32_t duration;
  uint8_t features;  ///< kFeature* bits of what its channels and keys use
};

enum ImageStatus : uint8_t {
  kImageOk = 0,
  kImageTooShort,
  kImageBadMagic,
  kImageBadVersion,
  kImageBadChannelCount,
  kImageBadTicksPerSecond,
  kImageBadChannel,    ///< a channel record or key that does not decode within the image
  kImageNeedsFeature,  ///< a segment family or channel feature this build left out (config.hpp)
};

/// Reads and checks an image's header and every channel record and key, whole, before anything
/// plays. On kImageOk and kImageNeedsFeature (the image is sound, this build cannot play it),
/// `header` is filled.
ImageStatus check_image(const uint8_t* image, uint32_t size, ShowHeader& header);

/// The offset of channel c's record (c < header.channel_count of a checked image).
uint32_t channel_offset(const uint8_t* image, uint8_t channel);

}  // namespace device
}  // namespace avar
