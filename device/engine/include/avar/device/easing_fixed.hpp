#pragma once
// Blender's easing equations (Robert Penner's, as avar's double engine has them in
// playback/runtime/src/easing.cpp) in Q30 integers. Freestanding C++14.

#include <stdint.h>

namespace avar {
namespace device {

/// The eased fraction of the change at normalised time t (Q30, 0 <= t < 2^30), Q30, for the
/// families sine .. bounce (SegmentKind) and an EasingMode; back_q30 is back's overshoot.
int64_t ease_fraction_q30(uint8_t kind, uint8_t easing, int64_t t, int64_t back_q30);

/// An elastic segment's numbers that do not change along it (derived once per segment).
struct ElasticSegment {
  uint8_t easing;
  bool blended;         ///< Blender's "elastic blend": amplitude 0 or below |change|
  int64_t change;       ///< Q8 output units
  int64_t amplitude;    ///< Q8: the wave's amplitude (the change when blended)
  int64_t factor;       ///< Q30: the blend's factor f (amplitude / |change|, or 0)
  int64_t shift;        ///< Q30 of the duration: Blender's s
  uint64_t per_shift;   ///< 2^60 / shift: for the blend's l = reach / shift
  uint64_t per_period;  ///< 2^62 / period (Q30 of the duration): phase in turns
};

/// An elastic segment from its change and the image's parameters: blended, the blend's factor
/// (Q30) or the wave's amplitude (Q8), the period and Blender's shift s (Q30 of the duration).
/// The exporter derives the shift (an arcsine) and the factor from the unrounded curve: near
/// |change| = amplitude the arcsine magnifies any rounding of the change.
ElasticSegment elastic_segment(uint8_t easing, int64_t change, bool blended, int64_t factor_or_amplitude, uint64_t period,
                               int64_t shift);
/// The elastic segment's offset from its start value at normalised time t (Q30), Q8.
int64_t elastic_offset_q8(const ElasticSegment& e, int64_t t);

}  // namespace device
}  // namespace avar
