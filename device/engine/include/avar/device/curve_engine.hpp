#pragma once
// The device curve engine: a channel of a show image sampled at an integer tick, in integers only.
// The same source runs on the host (avar sample --engine device, the tests, the simulated device)
// and on every microcontroller target; avar's double engine (playback/runtime/curve.hpp) is the
// reference it follows, to within 1 output unit of 16 bits: the same segment families, Blender's
// easing equations, the Cycles modifier, constant and linear extrapolation, and avar's key snap.
//
// Real-time contract: no allocation, no recursion, no floating point; a sample inside the
// segment of the last sample costs one segment evaluation (a Bezier segment: 24 fixed
// bisection steps of its time polynomial and the value cubic); entering the next segment decodes
// one key; any other jump re-reads the channel's keys from its first. Freestanding C++14.

#include <stdint.h>

#include "avar/device/show_image.hpp"

namespace avar {
namespace device {

/// What sampling needs of one channel of a checked image, read once (open_channel).
struct Channel {
  const uint8_t* image;
  uint32_t size;
  uint32_t keys_at;  ///< offset of the first key
  uint32_t ticks_per_second;
  uint16_t key_count;
  uint8_t flags;  ///< kChannelLinearExtrapolation, kChannelCycles
  uint8_t snap_ticks;
  int32_t start, end;               ///< first and last key's ticks
  int32_t first_value, last_value;  ///< output units
#if AVAR_DEVICE_CYCLES
  uint8_t cycle_before, cycle_after;  ///< CycleMode
  uint32_t before_count, after_count;
  int64_t cycle_offset;  ///< Q8 output units: last key's value - first key's
#endif
#if AVAR_DEVICE_EXTRAPOLATION
  int64_t slope_before, slope_after;  ///< Q8 output units per second
#endif
};

/// The segment a channel last sampled, decoded: one per channel per player, owned by the caller
/// (RAM). Results never depend on it: it only saves decoding.
struct SegmentCache {
  uint16_t index;       ///< the key that starts the segment; kNoSegment before the first sample
  uint32_t next_at;     ///< offset of the next key's record
  int32_t t0, t1;       ///< ticks
  int32_t k0, k1;       ///< the keys' values, output units
  uint32_t reciprocal;  ///< (t - t0) * reciprocal >> shift is the normalised time in Q30
  uint8_t shift;
  uint8_t kind, easing;
  /// The value polynomial's coefficients and v0 add up to less than 2^31 in magnitude: every
  /// step of its evaluation fits a 32-bit word (the fast path on small cores).
  bool narrow;
  int64_t v0;          ///< Q8
  int64_t c1, c2, c3;  ///< value polynomial (Q8) in s or, for Bezier, in u; easing: c1 the change
  uint32_t ta, tb;     ///< Bezier: the handles' times, Q30 of the segment
#if AVAR_DEVICE_EASINGS
  /// Easing parameters: back: p0 the overshoot (Q30); elastic: p0 1 when blended, p1 the wave's
  /// amplitude (Q8), p2 the blend's factor (Q30), p3 the shift (Q30 of the duration), q0 and q1
  /// the reciprocals of the shift and the period (ElasticSegment).
  int64_t p0, p1, p2, p3;
  uint64_t q0, q1;
#endif
};
const uint16_t kNoSegment = 0xffffu;

/// Reads channel `index` of an image that check_image accepted. Returns false for an index out of
/// range or a record that does not decode.
bool open_channel(const uint8_t* image, uint32_t size, uint8_t index, Channel& channel);
/// An empty cache (kNoSegment).
void reset_cache(SegmentCache& cache);

/// The channel's value at `tick` in Q8 output units (1/256 of an output unit), not saturated.
int64_t sample_q8(const Channel& channel, SegmentCache& cache, int32_t tick);
/// The channel's 16-bit output at `tick`: sample_q8 rounded to the nearest unit and saturated to
/// 0..65535 (the channel's range).
uint16_t sample(const Channel& channel, SegmentCache& cache, int32_t tick);

}  // namespace device
}  // namespace avar
