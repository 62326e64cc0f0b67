#pragma once
// A RawCurve as a flat array of doubles, every field explicit: how the curve engine's keys cross
// into another build of the engine (the studio page's WebAssembly) without a parser on that
// side. Enumerations are their underlying values; an absent handle, handle type or slope is a
// presence flag of 0.
//
//   header (kHeaderFields): format (1), key count, extrapolation, auto_smoothing,
//                           cycles before, after, before_count, after_count
//   per key (kKeyFields):   time, value, interpolation, easing, back, amplitude, period,
//                           has_left, left time, left value, left type (-1: none),
//                           has_right, right time, right value, right type (-1: none),
//                           has_in_slope, in_slope, has_out_slope, out_slope,
//                           tension, continuity, bias
//
// Pure; allocates (the vector). decode validates the layout and every enumeration and count
// (std::invalid_argument naming the field); the keys' own rules are Curve::build's.

#include <cstddef>
#include <span>
#include <vector>

#include "avar/playback/runtime/keys.hpp"

namespace avar::playback {

inline constexpr std::size_t kRawCurveHeaderFields = 8;
inline constexpr std::size_t kRawCurveKeyFields = 22;
inline constexpr double kRawCurveFormat = 1;

std::vector<double> encode_raw_curve(const RawCurve& curve);
RawCurve decode_raw_curve(std::span<const double> flat);

}  // namespace avar::playback
