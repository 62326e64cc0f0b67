#pragma once
// Keyframe curves. A RawCurve is the editable form (keys as loaded or authored); Curve::build
// validates it once and precomputes what evaluation needs, giving an immutable runtime curve.
// Evaluation follows Blender's F-curves: a key's interpolation shapes the segment that starts
// at it, and Bezier segments are evaluated by solving the time cubic for the parameter, then
// evaluating the value cubic. Times in seconds, values in channel units.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::playback {

enum class Interpolation { step, linear, bezier };

std::optional<Interpolation> interpolation_from_name(std::string_view name);
const char* to_string(Interpolation i);

/// A Bezier handle, absolute: (seconds, channel units).
struct Handle {
  double time = 0;
  double value = 0;
};

struct RawKey {
  double time = 0;
  double value = 0;
  Interpolation interpolation = Interpolation::linear;  ///< of the segment from this key to the next
  std::optional<Handle> left;                           ///< needed when the previous segment is Bezier
  std::optional<Handle> right;                          ///< needed when this key's segment is Bezier
  SourceLocation where;
};

struct RawCurve {
  std::vector<RawKey> keys;
  SourceLocation where;
};

/// Where sequential sampling left off; one per curve per sampler.
struct CurveCursor {
  std::size_t segment = 0;
};

class Curve {
 public:
  /// Validates the whole curve and builds it. Throws InputError at the offending key: no keys,
  /// non-finite times or values, times not strictly increasing, a Bezier segment without the
  /// start key's right handle or the end key's left handle, non-finite handles.
  static Curve build(const RawCurve& raw);

  /// Value at t (seconds). Before the first key: the first value; after the last: the last.
  /// Sequential calls with slowly increasing t cost O(1) thanks to the cursor; any t is
  /// correct. Real-time safe: no allocation, no exception.
  double evaluate(double t, CurveCursor& cursor) const noexcept;
  /// Random access (binary search). Real-time safe.
  double evaluate(double t) const noexcept;

  double start_time() const noexcept { return segments_.front().t0; }
  double end_time() const noexcept { return segments_.back().t0; }
  std::size_t key_count() const noexcept { return segments_.size(); }

 private:
  /// Segment i runs from key i to key i+1; the last entry is the last key alone.
  struct Segment {
    double t0 = 0;
    double v0 = 0;
    Interpolation interpolation = Interpolation::linear;
    double t1 = 0, v1 = 0;      ///< end key
    double tx[4] = {0, 0, 0, 0};  ///< Bezier time control points, corrected as Blender does
    double vy[4] = {0, 0, 0, 0};  ///< Bezier value control points
    bool flat = false;          ///< all four Bezier values equal: the value is constant
  };
  double evaluate_segment(const Segment& s, double t) const noexcept;
  std::size_t find_segment(double t) const noexcept;

  std::vector<Segment> segments_;
};

}  // namespace avar::playback
