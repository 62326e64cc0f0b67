#pragma once
// Keyframe curves. A RawCurve is the editable form (keys as loaded or authored); Curve::build
// validates it once and precomputes what evaluation needs, giving an immutable runtime curve.
// Evaluation follows Blender's F-curves: a key's interpolation shapes the segment that STARTS at
// that key; Bezier segments correct their handles as Blender does, solve the time cubic for the
// curve parameter (Blender's root when there are several) and evaluate the value cubic there.
// Outside the keys the curve holds the first / last key's value. Times in seconds, values in
// channel units.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::playback {

enum class Interpolation { step, linear, bezier };

/// "step", "linear" or "bezier"; nullopt for anything else.
std::optional<Interpolation> interpolation_from_name(std::string_view name);
/// The name interpolation_from_name accepts.
const char* to_string(Interpolation interpolation);

/// A Bezier handle, absolute: (seconds, channel units).
struct Handle {
  double time = 0;
  double value = 0;
};

struct RawKey {
  double time = 0;   ///< seconds
  double value = 0;  ///< channel units
  Interpolation interpolation = Interpolation::linear;  ///< of the segment from this key to the next
  std::optional<Handle> left;                           ///< needed when the previous segment is Bezier
  std::optional<Handle> right;                          ///< needed when this key's segment is Bezier
  SourceLocation where;
};

struct RawCurve {
  std::vector<RawKey> keys;
  SourceLocation where;
};

/// Where sequential sampling left off: one per curve per sampler, owned by the caller.
struct CurveCursor {
  std::size_t segment = 0;
};

class Curve {
 public:
  /// A curve without keys: evaluates to 0 everywhere. Curve::build never returns one.
  Curve() = default;

  /// Validates the whole curve and builds it. Throws InputError at the offending key (at
  /// raw.where when there are no keys), saying what was found and what was expected: no keys,
  /// non-finite times or values, times not strictly increasing, a Bezier segment without the
  /// start key's right handle or the end key's left handle, non-finite handles. Load-time only:
  /// allocates.
  static Curve build(const RawCurve& raw);

  /// Value at t (seconds). At or before the first key: the first key's value; at or after the
  /// last: the last key's value (also for a NaN t, which counts as before the start). Sequential
  /// calls whose t moves forward by less than a few segments cost O(1) thanks to the cursor; any
  /// other t (backwards, far ahead) falls back to a binary search, and the result never depends
  /// on the cursor: it equals evaluate(t) bit for bit. Real-time safe: no allocation, exception
  /// or lock. The curve is immutable, so many threads may evaluate it at once, each with its own
  /// cursor.
  double evaluate(double t, CurveCursor& cursor) const noexcept;
  /// Random access (binary search over the keys). Real-time safe, thread-safe.
  double evaluate(double t) const noexcept;

  double start_time() const noexcept { return start_; }  ///< first key's time (s); 0 without keys
  double end_time() const noexcept { return end_; }      ///< last key's time (s); 0 without keys
  std::size_t key_count() const noexcept { return times_.size(); }

 private:
  enum class Shape : std::uint8_t {
    step,             ///< the start key's value
    linear,           ///< start + s (end - start)
    constant,         ///< a Bezier segment whose four values agree (Blender's shortcut)
    bezier_table,     ///< Bezier, time strictly increasing in u: tabulated inverse + refinement
    bezier_closed,    ///< Bezier with handles that let time stall or run backwards: Blender's solve
  };
  /// Segment i runs from key i to key i+1. Times are normalised: s = (t - t0) / (t1 - t0).
  struct Segment {
    double t0 = 0;
    double inv_duration = 0;
    double v0 = 0;
    double e1 = 0, e2 = 0, e3 = 0;  ///< value cubic in u (linear: e1 = v1 - v0, in s)
    double k1 = 0, k2 = 0, k3 = 0;  ///< normalised time cubic s(u) = k1 u + k2 u^2 + k3 u^3
    std::uint32_t table = 0;        ///< first entry of this segment's inverse table
    Shape shape = Shape::step;
  };
  /// Cubic Hermite piece of the inverse u(s) on one of kTablePieces equal intervals of s, in the
  /// local coordinate w in [0, 1): u = a0 + a1 w + a2 w^2 + a3 w^3, then `refinements` steps.
  struct InversePiece {
    double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
    int refinements = 0;
  };
  static constexpr int kTablePieces = 16;
  static constexpr int kMaxRefinements = 2;

  static void tabulate_inverse(Segment& segment, std::vector<InversePiece>& table);
  static double refine(const Segment& s, const InversePiece& p, double w, double x, double& residual) noexcept;
  double evaluate_in(std::size_t segment, double t) const noexcept;
  double evaluate_bezier_closed(const Segment& s, double normalised_time) const noexcept;
  std::size_t find_segment(double t) const noexcept;

  std::vector<double> times_;         ///< key times
  std::vector<Segment> segments_;     ///< times_.size() - 1 of them
  std::vector<InversePiece> inverse_; ///< kTablePieces per bezier_table segment
  double start_ = 0, end_ = 0;
  double first_value_ = 0, last_value_ = 0;
};

}  // namespace avar::playback
