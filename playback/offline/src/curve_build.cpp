// Curve::build: validation, handle solving and the construction of a runtime curve's segments
// and inverse tables (the offline half of curve.hpp's Curve).
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "avar/core/bit_cast.hpp"
#include "avar/core/format.hpp"
#include "avar/playback/offline/handles.hpp"
#include "avar/playback/runtime/bezier_time_solve.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/easing.hpp"

namespace avar::playback {

// Curve's friend: fills Curve::build's curve with its segments, extras and inverse tables.
class CurveBuilder {
 public:
  using Shape = Curve::Shape;
  using Segment = Curve::Segment;
  using SegmentExtra = Curve::SegmentExtra;
  using InversePiece = Curve::InversePiece;
  using TableHeader = Curve::TableHeader;
  using Tables = Curve::Tables;
  static constexpr double kWindowLow = Curve::kWindowLow;
  static constexpr double kWindowHigh = Curve::kWindowHigh;
  static constexpr double kMaxResidual = Curve::kMaxResidual;
  static constexpr std::uint32_t kMinTablePieces = Curve::kMinTablePieces;
  static constexpr std::uint32_t kMaxTablePieces = Curve::kMaxTablePieces;

  /// A built curve and what it was built from: where segments() may copy Bezier segments from.
  struct Previous {
    const Curve& curve;
    const RawCurve& raw;
    std::vector<ResolvedHandles> handles;
  };
  static void segments(Tables& curve, const RawCurve& raw, const std::vector<ResolvedHandles>& handles,
                       const Previous* previous = nullptr);
  /// Copies `previous`'s segment j (its extra and inverse table with it) as the next of `curve`.
  static Segment copied(Tables& curve, const Curve& previous, std::size_t j);
  static Curve build(const RawCurve& raw, const Previous* previous);
  static void extrapolation(Curve& curve, const Tables& tables, const RawCurve& raw, const std::vector<ResolvedHandles>& handles);
  /// Appends the header, pieces and last entry of s's inverse table; returns how many pieces.
  static std::uint32_t tabulate_inverse(double k1, double k2, double k3, std::vector<InversePiece>& table);
};

namespace {

constexpr double kWindowLow = CurveBuilder::kWindowLow;
constexpr double kWindowHigh = CurveBuilder::kWindowHigh;
constexpr double kMaxResidual = CurveBuilder::kMaxResidual;
// The least slope of s(u) over Blender's window for which a Bezier segment is tabulated (see
// Curve::kWindowLow): below it the segment takes Blender's closed-form solve.
constexpr double kMinTableSlope = 0.1;

// Handles at thirds of the segment in time make s(u) = u, up to rounding of the handle times
// (~1e-13 of the segment). Within kMaxResidual of the identity on [0, 1], u = s is as close to
// the root as the tabulated inverse guarantees (|s(u) - s| <= kMaxResidual, s'(u) ~ 1).
bool time_is_parameter(const Cubic& s) noexcept { return std::abs(s.c1 - 1.0) + std::abs(s.c2) + std::abs(s.c3) <= kMaxResidual; }

double min_slope_on_window(const Cubic& s) noexcept {
  double low = std::min(s.slope_at(kWindowLow), s.slope_at(kWindowHigh));
  if (s.c3 != 0.0) {
    const double vertex = -s.c2 / (3.0 * s.c3);
    if (vertex > kWindowLow && vertex < kWindowHigh) low = std::min(low, s.slope_at(vertex));
  }
  return low;
}

// u in [0, 1] with s(u) = target, for s strictly increasing on [0, 1] with s(0) = 0, s(1) = 1:
// Newton's steps from `guess`, kept inside the bracket that the signs of s(u) - target leave
// (halving it when a step would leave it), until u stops moving; to the last bit or so.
double invert_increasing(const Cubic& s, double target, double guess) noexcept {
  double lo = 0.0, hi = 1.0, u = std::clamp(guess, lo, hi);
  for (int i = 0; i < 100; ++i) {
    const double residual = s.at(u) - target;
    if (residual == 0.0) break;
    (residual < 0.0 ? lo : hi) = u;
    double next = u - residual / s.slope_at(u);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next <= lo || next >= hi || next == u) break;
    u = next;
  }
  return u;
}

constexpr double binomial(int n, int k) noexcept {
  double c = 1;  // C(n - k + i, i) after step i: exact integers
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// Bernstein coefficients on [0, 1] of the polynomial with power coefficients p[0..Degree]:
// b_i = sum over k <= i of C(i, k) / C(Degree, k) p_k. The polynomial's values on [0, 1] are
// convex combinations of them, so their least and greatest bound it on the whole interval.
template <int Degree>
std::pair<double, double> bernstein_range(const std::array<double, Degree + 1>& p) noexcept {
  static constexpr auto weights = [] {
    std::array<std::array<double, Degree + 1>, Degree + 1> w{};
    for (int i = 0; i <= Degree; ++i)
      for (int k = 0; k <= i; ++k)
        w[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = binomial(i, k) / binomial(Degree, k);
    return w;
  }();
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t i = 0; i <= Degree; ++i) {
    double b = 0;
    for (std::size_t k = 0; k <= i; ++k) b += weights[i][k] * p[k];
    low = std::min(low, b), high = std::max(high, b);
  }
  return {low, high};
}

std::string seconds(double t) { return format_number(t) + " s"; }

void require_finite(const RawKey& k, double x, const char* what) {
  if (!std::isfinite(x))
    throw InputError(k.where, std::string("the ") + what + " of the key at " + seconds(k.time) + " is " + format_number(x) +
                                  "; expected a finite number");
}

void validate(const RawCurve& raw) {
  if (raw.keys.empty()) throw InputError(raw.where, "the track has no keys; expected at least one key");
  if (raw.cycles.before_count < 0 || raw.cycles.after_count < 0)
    throw InputError(raw.where, "a cycle count is negative; expected 0 (forever) or more cycles");
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    if (!std::isfinite(k.time))
      throw InputError(k.where, "key time " + format_number(k.time) + " is not a number of seconds; expected a finite time");
    if (!std::isfinite(k.value))
      throw InputError(
          k.where, "key value " + format_number(k.value) + " at " + seconds(k.time) + " is not finite; expected a finite value");
    if (i > 0 && !(k.time > raw.keys[i - 1].time))
      throw InputError(k.where, "key time " + seconds(k.time) + " is not after the previous key's " +
                                    seconds(raw.keys[i - 1].time) + "; key times must strictly increase");
    for (const auto& [handle, side] : {std::pair{&k.left, "left"}, std::pair{&k.right, "right"}})
      if (*handle && (!std::isfinite((*handle)->time) || !std::isfinite((*handle)->value)))
        throw InputError(k.where, std::string("the ") + side + " handle of the key at " + seconds(k.time) + " is [" +
                                      format_number((*handle)->time) + ", " + format_number((*handle)->value) +
                                      "]; expected a finite [time, value]");
    for (const auto& [type, handle, side] :
         {std::tuple{k.left_type, k.left.has_value(), "left"}, std::tuple{k.right_type, k.right.has_value(), "right"}})
      if (type && (*type == HandleType::free || *type == HandleType::aligned) && !handle)
        throw InputError(k.where, std::string("the ") + side + " handle of the key at " + seconds(k.time) + " is " +
                                      to_string(*type) + " but not given; expected " + side + ": [time, value], or " + side +
                                      "_type auto, auto_clamped or vector to compute it");
    require_finite(k, k.back, "back");
    require_finite(k, k.amplitude, "amplitude");
    require_finite(k, k.period, "period");
    require_finite(k, k.tension, "tension");
    require_finite(k, k.continuity, "continuity");
    require_finite(k, k.bias, "bias");
    if (k.in_slope) require_finite(k, *k.in_slope, "in_slope");
    if (k.out_slope) require_finite(k, *k.out_slope, "out_slope");
  }
  for (std::size_t i = 0; i + 1 < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    const RawKey& next = raw.keys[i + 1];
    if (k.interpolation != Interpolation::hermite) continue;
    if (!k.out_slope)
      throw InputError(k.where, "the key at " + seconds(k.time) +
                                    " starts a hermite segment but has no out_slope; expected out_slope: <units per second>");
    if (!next.in_slope)
      throw InputError(next.where, "the key at " + seconds(next.time) +
                                       " ends a hermite segment but has no in_slope; expected in_slope: <units per second>");
  }
}

// Chord slopes around key i (units per second); a missing side takes the other's.
std::pair<double, double> chord_slopes(const RawCurve& raw, std::size_t i) {
  const auto& k = raw.keys;
  const auto slope = [&](std::size_t a) { return (k[a + 1].value - k[a].value) / (k[a + 1].time - k[a].time); };
  if (k.size() < 2) return {0, 0};
  const double before = i > 0 ? slope(i - 1) : slope(i);
  const double after = i + 1 < k.size() ? slope(i) : slope(i - 1);
  return {before, after};
}

// Kochanek-Bartels tangents of key i from its own tension, continuity and bias, in units per
// second: the chords' slopes weighted as in the TCB formulas. Zero parameters give the mean of
// the two chord slopes (Catmull-Rom); continuity 0 makes both tangents equal (C1).
std::pair<double, double> tcb_tangents(const RawCurve& raw, std::size_t i) {
  const RawKey& k = raw.keys[i];
  const auto [before, after] = chord_slopes(raw, i);
  const double t = k.tension, c = k.continuity, b = k.bias;
  const double in = (1 - t) / 2 * ((1 + b) * (1 - c) * before + (1 - b) * (1 + c) * after);
  const double out = (1 - t) / 2 * ((1 + b) * (1 + c) * before + (1 - b) * (1 - c) * after);
  return {in, out};
}

double handle_slope(const Handle& h, const RawKey& k) {
  const double dt = k.time - h.time;
  return dt == 0 ? 0.0 : (k.value - h.value) / dt;
}

}  // namespace

Curve Curve::build(const RawCurve& raw) { return CurveBuilder::build(raw, nullptr); }

Curve Curve::build(const RawCurve& raw, const Curve& previous, const RawCurve& previous_raw) {
  if (previous.key_count() != previous_raw.keys.size()) return CurveBuilder::build(raw, nullptr);
  const CurveBuilder::Previous p{previous, previous_raw, compute_handles(previous_raw)};
  return CurveBuilder::build(raw, &p);
}

Curve CurveBuilder::build(const RawCurve& raw, const Previous* previous) {
  validate(raw);
  Curve curve;
  Tables tables;
  tables.times.reserve(raw.keys.size());
  for (const RawKey& k : raw.keys) tables.times.push_back(k.time);
  curve.start_ = raw.keys.front().time;
  curve.end_ = raw.keys.back().time;
  curve.first_value_ = raw.keys.front().value;
  curve.last_value_ = raw.keys.back().value;
  curve.cycles_ = raw.cycles;
  const std::vector<ResolvedHandles> handles = compute_handles(raw);
  segments(tables, raw, handles, previous);
  extrapolation(curve, tables, raw, handles);
  curve.adopt(std::move(tables));
  return curve;
}

CurveBuilder::Segment CurveBuilder::copied(Tables& curve, const Curve& previous, std::size_t j) {
  Segment s = previous.segments_[j];
  if (s.shape == Shape::bezier_table) {
    // Header, pieces, and the u = 1 entry.
    const std::size_t header = s.extra - 1;
    const auto pieces = static_cast<std::size_t>(avar::bit_cast<TableHeader>(previous.inverse_[header]).pieces);
    const InversePiece* first = previous.inverse_ + header;
    s.extra = static_cast<std::uint32_t>(curve.inverse.size()) + 1;
    curve.inverse.insert(curve.inverse.end(), first, first + static_cast<std::ptrdiff_t>(pieces + 2));
  } else if (s.shape == Shape::bezier_closed) {
    const SegmentExtra extra = previous.extras_[s.extra];
    s.extra = static_cast<std::uint32_t>(curve.extras.size());
    curve.extras.push_back(extra);
  }
  return s;
}

void CurveBuilder::segments(Tables& curve, const RawCurve& raw, const std::vector<ResolvedHandles>& handles,
                            const Previous* previous) {
  const std::size_t n = raw.keys.size();
  curve.segments.reserve(n - 1);
  // A Bezier segment of `previous` built from the same two keys and handles as segment i (the
  // same index, or as far from the end), if there is one.
  const auto reusable = [&](std::size_t i) -> std::optional<std::size_t> {
    if (!previous) return std::nullopt;
    const std::size_t old_n = previous->raw.keys.size();
    // Out of range as the same distance from the end: i + 1 + old_n <= n.
    const std::size_t from_end = i + old_n >= n ? i + old_n - n : old_n;
    for (const std::size_t j : {i, from_end}) {
      if (j + 1 >= old_n) continue;
      const RawKey &a = raw.keys[i], &b = raw.keys[i + 1], &pa = previous->raw.keys[j], &pb = previous->raw.keys[j + 1];
      if (pa.interpolation == Interpolation::bezier && same_bits(a.time, pa.time) && same_bits(a.value, pa.value) &&
          same_bits(b.time, pb.time) && same_bits(b.value, pb.value) &&
          same_handle(handles[i].right, previous->handles[j].right) &&
          same_handle(handles[i + 1].left, previous->handles[j + 1].left))
        return j;
    }
    return std::nullopt;
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const RawKey& k = raw.keys[i];
    const RawKey& next = raw.keys[i + 1];
    if (k.interpolation == Interpolation::bezier) {
      if (const std::optional<std::size_t> j = reusable(i)) {
        curve.segments.push_back(copied(curve, previous->curve, *j));
        continue;
      }
    }
    const double duration = next.time - k.time;
    const double change = next.value - k.value;
    Segment s;
    s.t0 = k.time;
    s.t1 = next.time;
    s.inv_duration = 1.0 / duration;
    s.v0 = k.value;
    s.family = k.interpolation;
    const auto hermite = [&](double m0, double m1) {
      s.shape = Shape::polynomial;
      s.e1 = duration * m0;
      s.e2 = 3 * change - 2 * duration * m0 - duration * m1;
      s.e3 = -2 * change + duration * m0 + duration * m1;
    };
    const auto with_extra = [&](Shape shape, double k1, double k2, double k3) -> SegmentExtra& {
      s.shape = shape;
      s.extra = static_cast<std::uint32_t>(curve.extras.size());
      return curve.extras.emplace_back(SegmentExtra{k1, k2, k3});
    };
    switch (k.interpolation) {
      case Interpolation::step: break;  // v0
      case Interpolation::linear: s.e1 = change; break;
      case Interpolation::hermite: hermite(*k.out_slope, *next.in_slope); break;
      case Interpolation::catmull_rom:
      case Interpolation::cardinal:
      case Interpolation::kochanek_bartels: hermite(tcb_tangents(raw, i).second, tcb_tangents(raw, i + 1).first); break;
      case Interpolation::bspline: {
        // Control points P[i-1..i+2]; beyond the ends the key sequence is reflected (2 P0 - P1),
        // which makes the spline start and end exactly on the first and last keys.
        const auto p = [&](std::ptrdiff_t j) {
          const auto last = static_cast<std::ptrdiff_t>(n) - 1;
          const auto v = [&](std::ptrdiff_t m) { return raw.keys[static_cast<std::size_t>(m)].value; };
          if (j < 0) return 2 * v(0) - v(1);
          if (j > last) return 2 * v(last) - v(last - 1);
          return v(j);
        };
        const auto at = static_cast<std::ptrdiff_t>(i);
        const double a = p(at - 1), b = p(at), c = p(at + 1), d = p(at + 2);
        s.shape = Shape::polynomial;
        s.v0 = (a + 4 * b + c) / 6;
        s.e1 = (c - a) / 2;
        s.e2 = (a - 2 * b + c) / 2;
        s.e3 = (-a + 3 * b - 3 * c + d) / 6;
        break;
      }
      case Interpolation::bezier: {
        const Handle right = *handles[i].right, left = *handles[i + 1].left;
        double time[4] = {k.time, right.time, left.time, next.time};
        double value[4] = {k.value, right.value, left.value, next.value};
        // Blender's shortcut, tested on the handles before correction: four equal values (to
        // float precision) make the segment constant.
        if (std::abs(value[0] - value[3]) < FLT_EPSILON && std::abs(value[1] - value[2]) < FLT_EPSILON &&
            std::abs(value[2] - value[3]) < FLT_EPSILON)
          break;  // v0
        correct_bezier_handles(time, value);
        // Time in units of the segment: s(u) runs from 0 to 1. The roots in u are those of the
        // cubic in seconds (or in Blender's frames): scaling time does not move them.
        const double unit_time[4] = {0.0, (time[1] - k.time) / duration, (time[2] - k.time) / duration, 1.0};
        const Cubic s_of_u = bezier_polynomial(unit_time);
        const Cubic v_of_u = bezier_polynomial(value);
        s.e1 = v_of_u.c1, s.e2 = v_of_u.c2, s.e3 = v_of_u.c3;
        if (time_is_parameter(s_of_u)) {
          s.shape = Shape::polynomial;  // in u = s
          break;
        }
        if (min_slope_on_window(s_of_u) >= kMinTableSlope && std::isfinite(kMaxTablePieces * s.inv_duration)) {
          s.shape = Shape::bezier_table;
          s.extra = static_cast<std::uint32_t>(curve.inverse.size()) + 1;                      // after the table's header
          s.inv_duration *= tabulate_inverse(s_of_u.c1, s_of_u.c2, s_of_u.c3, curve.inverse);  // a power of two: exact
        } else {
          with_extra(Shape::bezier_closed, s_of_u.c1, s_of_u.c2, s_of_u.c3);
        }
        break;
      }
      default:  // Blender's easing families
        s.easing = resolved_easing(k.interpolation, k.easing);
        s.e1 = change;
        with_extra(Shape::easing, k.back, k.amplitude, k.period);
        break;
    }
    curve.segments.push_back(s);
  }
}

// Blender's slope rules (fcurve_eval_keyframes_extrapolate): constant extrapolation, or an end
// key with constant interpolation, holds; an end key with linear interpolation continues the
// line to its neighbour; Bezier and easing end keys follow their outer handle. avar's splines
// continue with the slope of the curve at the end.
void CurveBuilder::extrapolation(Curve& curve, const Tables& tables, const RawCurve& raw,
                                 const std::vector<ResolvedHandles>& handles) {
  if (raw.extrapolation == Extrapolation::constant) return;
  const std::size_t n = raw.keys.size();
  const auto slope_at = [&](bool before) -> double {
    const std::size_t i = before ? 0 : n - 1;
    const RawKey& k = raw.keys[i];
    switch (k.interpolation) {
      case Interpolation::step: return 0;
      case Interpolation::linear: {
        if (n == 1) return 0;
        const RawKey& other = raw.keys[before ? 1 : n - 2];
        return (other.value - k.value) / (other.time - k.time);
      }
      case Interpolation::hermite:
      case Interpolation::catmull_rom:
      case Interpolation::cardinal:
      case Interpolation::kochanek_bartels:
      case Interpolation::bspline: {
        if (tables.segments.empty()) return 0;
        const Segment& s = before ? tables.segments.front() : tables.segments.back();
        if (s.shape != Shape::polynomial) return 0;
        return (before ? s.e1 : s.e1 + 2 * s.e2 + 3 * s.e3) * s.inv_duration;
      }
      default: {
        const std::optional<Handle>& h = before ? handles[i].left : handles[i].right;
        return h ? handle_slope(*h, k) : 0;
      }
    }
  };
  curve.slope_before_ = slope_at(true);
  curve.slope_after_ = slope_at(false);
}

// The inverse u(s) of a strictly increasing time cubic as equal pieces of s: on each, the quintic
// Hermite interpolant q(w) that matches u, du/ds = 1 / s'(u) and d2u/ds2 = -s''(u) / s'(u)^3 at
// both ends. The table has the fewest pieces (a power of two, kMinTablePieces to kMaxTablePieces)
// for which every piece is certified, or kMaxTablePieces, and one more entry, u = 1, for the
// normalised time 1 itself.
//
// Certification, the contract of a certified piece j of n: for every w in [0, 1], with
// x = (j + w) / n, the parameter u = q(w) lies in Blender's window and |s(u) - x| <= kMaxResidual,
// so that (s'(u) >= kMinTableSlope over the window) u is within 1e-9 of the one root there.
// r(w) = s(q(w)) - x is a polynomial of degree 15 in w and q one of degree 5: in the Bernstein
// basis of [0, 1] their values are convex combinations of their coefficients, whose extremes
// therefore bound them over the whole piece, not only at sample points. A piece is certified when
// its r coefficients are within kMaxResidual / 2 and its q coefficients within half the window's
// margins; the other halves cover rounding, orders of magnitude smaller: these coefficients in
// double (~1e-14), the quintic evaluated at run time (a few ulps of u <= 1, times s' <= 3), the
// piece's w exact (the fraction of (t - t0) * inv_duration, which is n x).
std::uint32_t CurveBuilder::tabulate_inverse(double k1, double k2, double k3, std::vector<InversePiece>& table) {
  static_assert(sizeof(TableHeader) == sizeof(InversePiece));
  const Cubic s{0.0, k1, k2, k3};
  constexpr std::uint32_t finest = kMaxTablePieces;
  // u, du/ds and d2u/ds2 at s = i / finest; coarser tables take every (finest / n)-th.
  std::array<double, finest + 1> u{}, du_ds{}, d2u_ds2{};
  constexpr double dx = 1.0 / finest;
  for (std::uint32_t i = 0; i <= finest; ++i) {
    // From the previous knot's Taylor step: a few Newton steps (the certification checks the result).
    u[i] = i == 0        ? 0.0
           : i == finest ? 1.0
                         : invert_increasing(s, i * dx, u[i - 1] + dx * (du_ds[i - 1] + 0.5 * dx * d2u_ds2[i - 1]));
    const double slope = s.slope_at(u[i]), bend = 2.0 * s.c2 + 6.0 * s.c3 * u[i];
    du_ds[i] = 1.0 / slope;
    d2u_ds2[i] = -bend / (slope * slope * slope);
  }
  const auto certified = [&](const InversePiece& q, double x0, double h) {
    const std::array<double, 6> q1{q.a0, q.a1, q.a2, q.a3, q.a4, q.a5};
    std::array<double, 11> q2{};
    std::array<double, 16> r{};
    for (std::size_t i = 0; i < 6; ++i)
      for (std::size_t k = 0; k < 6; ++k) q2[i + k] += q1[i] * q1[k];
    for (std::size_t i = 0; i < 11; ++i)
      for (std::size_t k = 0; k < 6; ++k) r[i + k] += s.c3 * (q2[i] * q1[k]);
    for (std::size_t i = 0; i < 11; ++i) r[i] += s.c2 * q2[i];
    for (std::size_t i = 0; i < 6; ++i) r[i] += s.c1 * q1[i];
    r[0] -= x0, r[1] -= h;
    const auto [r_low, r_high] = bernstein_range<15>(r);
    const auto [u_low, u_high] = bernstein_range<5>(q1);
    return -r_low <= kMaxResidual / 2 && r_high <= kMaxResidual / 2 && u_low >= kWindowLow / 2 &&
           u_high <= 1.0 + (kWindowHigh - 1.0) / 2;
  };
  const std::size_t header = table.size();
  for (std::uint32_t n = kMinTablePieces;; n *= 2) {
    table.resize(header + 1);
    const std::uint32_t stride = finest / n;
    const double h = 1.0 / n;  // ds/dw
    bool all_certified = true;
    // Below the finest table, the first uncertified piece is enough to try the next.
    for (std::uint32_t j = 0; j < n && (all_certified || n == finest); ++j) {
      const std::uint32_t a = j * stride, b = a + stride;
      const double step = u[b] - u[a], m0 = du_ds[a] * h, m1 = du_ds[b] * h, c0 = d2u_ds2[a] * h * h, c1 = d2u_ds2[b] * h * h;
      InversePiece piece{u[a],
                         m0,
                         0.5 * c0,
                         10.0 * step - 6.0 * m0 - 4.0 * m1 - 1.5 * c0 + 0.5 * c1,
                         -15.0 * step + 8.0 * m0 + 7.0 * m1 + 1.5 * c0 - c1,
                         6.0 * step - 3.0 * m0 - 3.0 * m1 - 0.5 * c0 + 0.5 * c1};
      if (!certified(piece, j * h, h)) {
        piece.a1 = -piece.a1;  // the mark of an uncertified piece: du/dw is positive
        all_certified = false;
      }
      table.push_back(piece);
    }
    if (all_certified || n == finest) {
      table[header] = avar::bit_cast<InversePiece>(TableHeader{k1, k2, k3, static_cast<double>(n), {0, 0}});
      // x == 1: u = 1 (uncertified by its a1 = 0, so checked; only t rounding onto t1 reads it).
      table.push_back(InversePiece{1.0, 0.0, 0.0, 0.0, 0.0, 0.0});
      return n;
    }
  }
}

}  // namespace avar::playback
