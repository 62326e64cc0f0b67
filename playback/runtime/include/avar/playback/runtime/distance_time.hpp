#pragma once
// Speed control by distance-time functions (Parent, Computer Animation, 3.2.3): s(t) maps
// normalised time t in [0, 1] to normalised distance s in [0, 1] along a path, s(0) = 0,
// s(1) = 1, continuous and non-decreasing. Multiply s by the path's length and look the distance
// up in an ArcLengthTable to move along a curve at the chosen speed profile.
//
// Shapes (k1, k2 are normalised times, 0 <= k1 <= k2 <= 1):
// - linear: s = t, constant speed.
// - sine: s = (1 - cos(pi t)) / 2, ease in and out, speed continuous.
// - sine_constant_middle: a quarter sine accelerates until k1, constant speed until k2, a quarter
//   sine decelerates to 1; speed continuous (Parent's ease(t) with sinusoidal pieces).
// - parabolic: constant acceleration until k1, constant speed until k2, constant deceleration to
//   1; speed continuous, acceleration piecewise constant.
// - cubic: s = 3t^2 - 2t^3, speed continuous and zero at both ends.
// - user: a keyframe curve of the animator's (time and value both normalised), validated at build.
// Evaluation is pure: no allocation, exception or lock.

#include <cstdint>
#include <optional>
#include <string_view>

#include "avar/playback/runtime/curve.hpp"

namespace avar::playback {

enum class DistanceTimeShape : std::uint8_t { linear, sine, sine_constant_middle, parabolic, cubic, user };

/// "linear", "sine", "sine_constant_middle", "parabolic", "cubic" (the built-in shapes; `user`
/// has no name: it comes from keys); nullopt for anything else.
std::optional<DistanceTimeShape> distance_time_shape_from_name(std::string_view name);
const char* to_string(DistanceTimeShape shape);

class DistanceTime {
 public:
  /// Throws std::invalid_argument unless 0 <= k1 <= k2 <= 1 (k1, k2 only matter for
  /// sine_constant_middle and parabolic).
  explicit DistanceTime(DistanceTimeShape shape, double k1 = 0, double k2 = 1);

  /// A user distance-time function from keyframe keys (key time: normalised time, key value:
  /// normalised distance; any interpolation). Throws InputError at the offending key unless the
  /// first key is at time 0 with value 0, the last at time 1 with value 1, and the built curve
  /// never decreases nor leaves [0, 1] at any of kUserSamplesPerSegment samples of each segment
  /// (besides Curve::build's own validation). Load time: allocates. Offline: defined by the
  /// offline layer (offline/src/distance_time_build.cpp), like Curve::build.
  static DistanceTime from_keys(const RawCurve& raw);
  static constexpr int kUserSamplesPerSegment = 256;

  /// s(t); t is clamped to [0, 1] (a NaN t gives 0).
  double distance(double t) const noexcept;
  /// ds/dt at t in [0, 1] (0 outside); for a user curve a central difference of step 1e-6.
  double speed(double t) const noexcept;

  DistanceTimeShape shape() const noexcept { return shape_; }
  double k1() const noexcept { return k1_; }
  double k2() const noexcept { return k2_; }
  /// The keys of a user curve as given (empty for the built-in shapes).
  const RawCurve& user_keys() const noexcept { return user_raw_; }

 private:
  DistanceTimeShape shape_;
  double k1_, k2_;
  double scale_ = 1;  ///< sine_constant_middle: 1 / the unnormalised total; parabolic: the top speed
  RawCurve user_raw_;
  Curve user_;
};

}  // namespace avar::playback
