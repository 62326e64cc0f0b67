#pragma once
// Keyframe curves at run time. A RawCurve (keys.hpp) is the editable form; Curve::build (the
// offline layer: offline/src/curve_build.cpp) validates it once and precomputes what evaluation
// needs, giving the immutable runtime curve this header evaluates.
//
// Evaluation follows Blender's F-curves (Blender 3.x/4.x, blenkernel fcurve.cc): a key's
// interpolation shapes the segment that STARTS at that key; Bezier segments correct their
// handles as Blender does, solve the time cubic for the curve parameter and evaluate the value
// cubic there; easing segments use Blender's easing equations; handles given only by their types
// (auto, auto_clamped, vector, aligned) are computed as Blender computes them, including its
// "continuous acceleration" auto smoothing and cycle-aware handles; outside the keys the curve
// extrapolates (constant or linear, Blender's slope rules) or repeats through a Cycles modifier.
// avar adds Hermite (explicit slopes), Catmull-Rom, cardinal, Kochanek-Bartels and uniform cubic
// B-spline segments. Times in seconds, values in channel units.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "avar/playback/runtime/keys.hpp"

namespace avar::playback {

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
  /// non-finite times, values, handles or parameters, times not strictly increasing, a free or
  /// aligned handle side used by a Bezier segment without its handle, a Hermite segment without
  /// its slopes, negative cycle counts. Load-time only: allocates. Offline: defined by the offline
  /// layer (avar::playback links it); avar_playback_runtime alone does not provide it.
  static Curve build(const RawCurve& raw);
  /// The same curve, built again after an edit of `previous_raw` (which built `previous`): a
  /// Bezier segment whose keys and resolved handles are those of a segment of `previous` at the
  /// same index, or at the same distance from the end, takes that segment's coefficients and
  /// inverse table instead of solving them again. The result is bit for bit Curve::build(raw)
  /// (what it copies was computed from the same numbers); an edit of a few keys of a long curve
  /// then costs its handles and the segments it changed, not the whole curve's tables.
  static Curve build(const RawCurve& raw, const Curve& previous, const RawCurve& previous_raw);

  /// A time within this many seconds of a key's time is that key's time, as Blender treats an
  /// evaluation time within 0.0001 frame of a key as the key: at a key the curve returns that
  /// key, even when the time was rounded on its way (a key at 11/6 s written with 12 digits, or a
  /// sample time on a nanosecond grid), and never the value just before it. 1 us is Blender's
  /// threshold at 100 fps (a quarter of it at 24 fps), a thousand times the rounding of any of
  /// those times and a thousandth of a 1 kHz tick. Snapping comes before extrapolation and
  /// cycling, so just before a cycled curve's first key is its first key, not the end of the
  /// cycle before (Blender's cycle map, which comes first there, gives the latter).
  static constexpr double kKeySnap = 1e-6;

  /// Value at t (seconds), extrapolated or cycled outside the keys; a NaN t counts as before
  /// the start. Within kKeySnap of a key, the value at that key. Sequential calls whose t moves forward by less than a few
  /// segments cost O(1) thanks to the cursor; any other t falls back to a binary search, and the result never depends on the
  /// cursor: it equals evaluate(t) bit for bit. Always finite. Real-time safe: no allocation, exception or lock. The curve is
  /// immutable, so many threads may evaluate it at once, each with its own cursor. Inline: the tick's common case (t strictly
  /// inside the cursor's segment) is one bounds check, two compares and, for polynomial segments, a cubic.
  double evaluate(double t, CurveCursor& cursor) const noexcept {
    if (cursor.segment < segment_count_) [[likely]] {
      const Segment& s = segments_[cursor.segment];
      if (t > s.t0 + kKeySnap && t < s.t1 - kKeySnap) [[likely]]
        return evaluate_in(s, t);
    }
    return evaluate_moved(t, cursor);
  }
  /// Random access (binary search over the keys). Real-time safe, thread-safe.
  double evaluate(double t) const noexcept;

  /// Reads what sampling with this cursor will need next: its segment and the one after it (the
  /// first one after the last, where a looping show wraps), each with the key time that ends it
  /// and, for a tabulated Bezier segment, its first piece. A tick that then crosses a key finds
  /// them in cache: data last read a whole loop of the show earlier otherwise cost the loop
  /// bench's wrap tick about 150 ns per curve. Returns a sum of what it read, for the caller to
  /// keep (so that the reads are not optimised away). Real-time safe, O(1).
  double warm(const CurveCursor& cursor) const noexcept;

  /// One segment as an exporter re-encodes it (the device engine's show image): its shape and
  /// the numbers that define it, exactly as this curve evaluates them.
  struct SegmentView {
    enum class Kind : std::uint8_t {
      constant,  ///< v0 (step, and Blender's flat Bezier)
      linear,    ///< v0 + s e1 in the normalised time s
      cubic,     ///< v0 + s (e1 + s (e2 + s e3)): the Hermite family, the B-spline, Bezier with time linear
      bezier,    ///< v0 + u (e1 + u (e2 + u e3)) where the time cubic k1 u + k2 u^2 + k3 u^3 = s
      easing,    ///< v0 + e1 * Blender's easing of `family` (elastic: its own equation)
    };
    Kind kind = Kind::constant;
    double t0 = 0, t1 = 0;  ///< the keys' times (s)
    double v0 = 0, e1 = 0, e2 = 0, e3 = 0;
    double k1 = 0, k2 = 0, k3 = 0;               ///< bezier
    Interpolation family = Interpolation::step;  ///< easing
    Easing easing = Easing::ease_in;             ///< easing: resolved (never automatic)
    double back = 0, amplitude = 0, period = 0;  ///< easing: the key's parameters
  };
  std::size_t segment_count() const noexcept { return segment_count_; }
  /// Segment i (i < segment_count()).
  SegmentView segment_view(std::size_t i) const noexcept;
  /// Linear extrapolation's slopes before the first key and after the last (units per second;
  /// 0 for constant extrapolation), and the Cycles modifier.
  double slope_before() const noexcept { return slope_before_; }
  double slope_after() const noexcept { return slope_after_; }
  const Cycles& cycles() const noexcept { return cycles_; }

  double start_time() const noexcept { return start_; }  ///< first key's time (s); 0 without keys
  double end_time() const noexcept { return end_; }      ///< last key's time (s); 0 without keys
  std::size_t key_count() const noexcept { return key_count_; }

 private:
  friend class CurveBuilder;  // the offline layer's builder fills the segments and tables

  enum class Shape : std::uint8_t {
    linear,  ///< v0 + s e1 in the normalised time s: linear, step and Blender's constant Bezier (e1 = 0)
    /// v0 + s (e1 + s (e2 + s e3)): the Hermite-family splines, the B-spline, and Bezier segments
    /// whose time handles sit at thirds (time linear in the parameter: u = s, no solve)
    polynomial,
    bezier_table,   ///< Bezier, time strictly increasing in u: tabulated inverse (certified pieces, or checked)
    bezier_closed,  ///< Bezier with handles that let time stall or run backwards: Blender's solve
    easing,         ///< one of Blender's easing equations
  };
  /// Segment i runs from key i to key i+1. Times are normalised: s = (t - t0) / (t1 - t0).
  /// One cache line: what every sample of the segment reads.
  struct alignas(64) Segment {
    double t0 = 0, t1 = 0;  ///< key times (s)
    /// 1 / (t1 - t0); bezier_table: pieces / (t1 - t0), a power of two times 1 / (t1 - t0), so
    /// that (t - t0) * inv_duration is exactly `pieces` times the normalised time: the index of
    /// the inverse's piece plus the position within it
    double inv_duration = 0;
    double v0 = 0;
    double e1 = 0, e2 = 0, e3 = 0;  ///< value cubic (in u for Bezier, in s otherwise)
    std::uint32_t extra = 0;        ///< bezier_closed, easing: index into extras_; bezier_table: of its first piece in inverse_
    Shape shape = Shape::linear;
    Interpolation family = Interpolation::step;  ///< easing segments
    Easing easing = Easing::automatic;           ///< easing segments
  };
  /// What the segments that solve or ease need beyond their Segment.
  struct SegmentExtra {
    double k1 = 0, k2 = 0, k3 = 0;  ///< bezier_closed: normalised time cubic s(u); easing: back, amplitude, period
  };
  /// Quintic Hermite piece of the inverse u(s) on one of a segment's equal intervals of s, in the
  /// local coordinate w in [0, 1): u = a0 + a1 w + ... + a5 w^5. A certified piece (a1 > 0, as
  /// du/dw always is) needs nothing more: the build proved |s(u) - s| <= kMaxResidual over its
  /// whole interval (see tabulate_inverse). An uncertified piece stores -a1; its samples check
  /// the residual, refine, and take Blender's solve when that is not enough (evaluate_uncertified).
  /// 48 bytes; a bezier_table segment costs its 64-byte Segment and (pieces + 2) * 48 bytes of
  /// table (header, pieces, u = 1): 8 to 64 pieces, about 2.9 KB on average for handles 0.1 to
  /// 0.6 of the segment long (the benchmark's).
  struct InversePiece {
    double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0;
    /// u at w, split as Estrin does: three independent pairs, a shorter dependency chain than Horner.
    double at(double w) const noexcept {
      const double w2 = w * w;
      return ((a0 + w * a1) + w2 * (a2 + w * a3)) + (w2 * w2) * (a4 + w * a5);
    }
  };
  /// The entry of inverse_ just before a table's first piece, as many bytes as a piece (read and
  /// written with bit_cast): what the table's uncertified pieces need.
  struct TableHeader {
    double k1 = 0, k2 = 0, k3 = 0;  ///< normalised time cubic s(u)
    double pieces = 0;              ///< how many equal pieces of s the table has
    double padding[2] = {0, 0};
  };
  static constexpr std::uint32_t kMinTablePieces = 8;
  static constexpr std::uint32_t kMaxTablePieces = 64;
  static_assert((kMaxTablePieces & (kMaxTablePieces - 1)) == 0 && kMaxTablePieces % kMinTablePieces == 0,
                "piece counts are powers of two: the piece index and position are exact");
  static constexpr int kMaxRefinements = 2;

  // Blender accepts time-cubic roots in [-1e-10, 1.000001]; a segment whose normalised time
  // s(u) rises at least kMinTableSlope (curve_build.cpp) over that whole window has exactly one
  // root there for every time, so any method that finds it finds Blender's root.
  static constexpr double kWindowLow = -1.0e-10;
  static constexpr double kWindowHigh = 1.000001;
  // Largest |s(u) - s| accepted from the tabulated inverse: with s'(u) >= kMinTableSlope the
  // parameter is then within 1e-9 of the root (Blender itself rounds the root to float, ~6e-8).
  static constexpr double kMaxResidual = 1.0e-10;

  /// The segment's value cubic at u (its normalised time for polynomial segments), split as
  /// Estrin does so that its halves evaluate in parallel: a shorter dependency chain than Horner.
  static double value_cubic(const Segment& s, double u) noexcept { return (s.v0 + u * s.e1) + (u * u) * (s.e2 + u * s.e3); }
  /// t within [s.t0, s.t1]. Inline with the table lookup of Bezier segments: a certified piece,
  /// the common case, is a quintic and the value cubic, with no call and no residual. The hint
  /// keeps polynomial segments (auto handles, the Hermite family, the B-spline) on the straight
  /// path, as they were before the table was inlined (GCC otherwise lays the table path there).
  double evaluate_in(const Segment& s, double t) const noexcept {
    const double x = (t - s.t0) * s.inv_duration;
    if (s.shape == Shape::linear) return s.v0 + x * s.e1;
    if (s.shape == Shape::polynomial) [[likely]]
      return value_cubic(s, x);
    if (s.shape == Shape::bezier_table) {
      // x in [0, pieces]: piece index and position; x == pieces (t rounds onto t1) reads the
      // table's last entry, u = 1.
      const auto j = static_cast<std::uint32_t>(x);
      const InversePiece& p = inverse_[s.extra + j];
      const double w = x - static_cast<double>(j);
      if (p.a1 > 0.0) return value_cubic(s, p.at(w));
      return evaluate_uncertified(s, p, w, x);
    }
    return evaluate_solved(s, x, t);
  }
  /// A bezier_table sample on an uncertified piece: the residual checked, up to kMaxRefinements
  /// steps, Blender's solve when that is not enough. scaled = pieces * normalised time.
  double evaluate_uncertified(const Segment& s, const InversePiece& p, double w, double scaled) const noexcept;
  /// bezier_closed and easing; x is the normalised time.
  double evaluate_solved(const Segment& s, double x, double t) const noexcept;
  /// Blender's solve of the time cubic k1 u + k2 u^2 + k3 u^3 = normalised_time, then the value.
  static double evaluate_bezier_closed(const Segment& s, double k1, double k2, double k3, double normalised_time) noexcept;
  /// evaluate(t, cursor) when t is not strictly inside the cursor's segment.
  double evaluate_moved(double t, CurveCursor& cursor) const noexcept;
  std::size_t find_segment(double t) const noexcept;
  double extrapolate(double t) const noexcept;
  /// Blender's Cycles time map: the time inside the keys to evaluate, and the value offset.
  double cycle_time(double t, double& offset) const noexcept;
  double evaluate_keys(double t, CurveCursor* cursor) const noexcept;
  /// t, or the first or last key's time when t is within kKeySnap of it.
  double snapped_to_ends(double t) const noexcept;

  /// What a build makes; a built curve never changes it, so copies of a curve share it (a copy
  /// of a show, made for each edit the studio hands to the figure, copies no tables).
  struct Tables {
    std::vector<double> times;          ///< key times
    std::vector<Segment> segments;      ///< times.size() - 1 of them
    std::vector<SegmentExtra> extras;   ///< one per bezier_closed and easing segment
    std::vector<InversePiece> inverse;  ///< pieces + 2 per bezier_table segment
  };
  /// Makes `tables` this curve's (the builder's last step).
  void adopt(Tables tables);

  std::shared_ptr<const Tables> tables_;
  // Into tables_, read where a sample reads them: one load each, as a vector's data would be.
  const double* times_ = nullptr;
  const Segment* segments_ = nullptr;
  const SegmentExtra* extras_ = nullptr;
  const InversePiece* inverse_ = nullptr;
  std::size_t key_count_ = 0;
  std::size_t segment_count_ = 0;
  double start_ = 0, end_ = 0;
  double first_value_ = 0, last_value_ = 0;
  double slope_before_ = 0, slope_after_ = 0;  ///< units per second; 0 for constant extrapolation
  Cycles cycles_;
};

}  // namespace avar::playback
