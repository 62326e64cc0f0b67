#pragma once
// The part of a show's curves that plays. Keys may lie before 0 or after the show's duration (a
// Blender scene keyed from frame 0 exports its first key at a negative time): they shape the curve
// inside [0, duration], and only that part moves the figure, so only that part is checked.

#include <algorithm>
#include <optional>

namespace avar::config::detail {

struct PlayedSpan {
  double t0 = 0, t1 = 0;  ///< seconds, t0 < t1
};

/// The part of [t0, t1] (seconds) within [0, duration]; none when nothing of it plays (a single
/// instant at an end included).
inline std::optional<PlayedSpan> played_part(double t0, double t1, double duration) {
  const double a = std::max(t0, 0.0);
  const double b = std::min(t1, duration);
  if (!(a < b)) return std::nullopt;
  return PlayedSpan{a, b};
}

/// Whether a key at time t (seconds) is played as it is: 0 <= t <= duration.
inline bool played(double t, double duration) { return t >= 0 && t <= duration; }

}  // namespace avar::config::detail
