#include "avar/playback/curve.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "avar/core/format.hpp"
#include "avar/playback/bezier_time_solve.hpp"

namespace avar::playback {
namespace {

// Blender accepts time-cubic roots in [-1e-10, 1.000001]; a segment whose normalised time
// s(u) rises at least this steeply over that whole window has exactly one root there for every
// time, so any method that finds it finds Blender's root.
constexpr double kWindowLow = -1.0e-10;
constexpr double kWindowHigh = 1.000001;
constexpr double kMinTableSlope = 0.1;
// Largest |s(u) - s| accepted from the tabulated inverse: with s'(u) >= kMinTableSlope the
// parameter is then within 1e-9 of the root (Blender itself rounds the root to float, ~6e-8).
constexpr double kMaxResidual = 1.0e-10;

double min_slope_on_window(const Cubic& s) noexcept {
  double low = std::min(s.slope_at(kWindowLow), s.slope_at(kWindowHigh));
  if (s.c3 != 0.0) {
    const double vertex = -s.c2 / (3.0 * s.c3);
    if (vertex > kWindowLow && vertex < kWindowHigh) low = std::min(low, s.slope_at(vertex));
  }
  return low;
}

// u in [0, 1] with s(u) = target, for s strictly increasing on [0, 1] with s(0) = 0, s(1) = 1.
double invert_increasing(const Cubic& s, double target) noexcept {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (s.at(mid) < target ? lo : hi) = mid;
  }
  return std::abs(s.at(lo) - target) <= std::abs(s.at(hi) - target) ? lo : hi;
}

std::string seconds(double t) { return format_number(t) + " s"; }

void validate(const RawCurve& raw) {
  if (raw.keys.empty()) throw InputError(raw.where, "the track has no keys; expected at least one key");
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    if (!std::isfinite(k.time))
      throw InputError(k.where, "key time " + format_number(k.time) + " is not a number of seconds; expected a finite time");
    if (!std::isfinite(k.value))
      throw InputError(k.where, "key value " + format_number(k.value) + " at " + seconds(k.time) + " is not finite; expected a finite value");
    if (i > 0 && !(k.time > raw.keys[i - 1].time))
      throw InputError(k.where, "key time " + seconds(k.time) + " is not after the previous key's " + seconds(raw.keys[i - 1].time) +
                                    "; key times must strictly increase");
    for (const auto& [handle, side] : {std::pair{&k.left, "left"}, std::pair{&k.right, "right"}})
      if (*handle && (!std::isfinite((*handle)->time) || !std::isfinite((*handle)->value)))
        throw InputError(k.where, std::string("the ") + side + " handle of the key at " + seconds(k.time) + " is [" +
                                      format_number((*handle)->time) + ", " + format_number((*handle)->value) +
                                      "]; expected a finite [time, value]");
  }
  for (std::size_t i = 0; i + 1 < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    const RawKey& next = raw.keys[i + 1];
    if (k.interpolation != Interpolation::bezier) continue;
    if (!k.right)
      throw InputError(k.where, "the key at " + seconds(k.time) + " starts a bezier segment but has no right handle; expected right: [time, value]");
    if (!next.left)
      throw InputError(next.where, "the key at " + seconds(next.time) + " ends a bezier segment but has no left handle; expected left: [time, value]");
  }
}

}  // namespace

std::optional<Interpolation> interpolation_from_name(std::string_view name) {
  if (name == "step") return Interpolation::step;
  if (name == "linear") return Interpolation::linear;
  if (name == "bezier") return Interpolation::bezier;
  return std::nullopt;
}

const char* to_string(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::step: return "step";
    case Interpolation::linear: return "linear";
    case Interpolation::bezier: return "bezier";
  }
  return "linear";
}

Curve Curve::build(const RawCurve& raw) {
  validate(raw);
  Curve curve;
  const std::size_t n = raw.keys.size();
  curve.times_.reserve(n);
  for (const RawKey& k : raw.keys) curve.times_.push_back(k.time);
  curve.start_ = raw.keys.front().time;
  curve.end_ = raw.keys.back().time;
  curve.first_value_ = raw.keys.front().value;
  curve.last_value_ = raw.keys.back().value;
  curve.segments_.reserve(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const RawKey& k = raw.keys[i];
    const RawKey& next = raw.keys[i + 1];
    const double duration = next.time - k.time;
    Segment s;
    s.t0 = k.time;
    s.inv_duration = 1.0 / duration;
    s.v0 = k.value;
    switch (k.interpolation) {
      case Interpolation::step: s.shape = Shape::step; break;
      case Interpolation::linear:
        s.shape = Shape::linear;
        s.e1 = next.value - k.value;
        break;
      case Interpolation::bezier: {
        double time[4] = {k.time, k.right->time, next.left->time, next.time};
        double value[4] = {k.value, k.right->value, next.left->value, next.value};
        // Blender's shortcut, tested on the handles as authored: four equal values (to float
        // precision) make the segment constant.
        if (std::abs(value[0] - value[3]) < FLT_EPSILON && std::abs(value[1] - value[2]) < FLT_EPSILON &&
            std::abs(value[2] - value[3]) < FLT_EPSILON) {
          s.shape = Shape::constant;
          break;
        }
        correct_bezier_handles(time, value);
        // Time in units of the segment: s(u) runs from 0 to 1. The roots in u are those of the
        // cubic in seconds (or in Blender's frames): scaling time does not move them.
        const double unit_time[4] = {0.0, (time[1] - k.time) / duration, (time[2] - k.time) / duration, 1.0};
        const Cubic s_of_u = bezier_polynomial(unit_time);
        const Cubic v_of_u = bezier_polynomial(value);
        s.k1 = s_of_u.c1, s.k2 = s_of_u.c2, s.k3 = s_of_u.c3;
        s.e1 = v_of_u.c1, s.e2 = v_of_u.c2, s.e3 = v_of_u.c3;
        if (min_slope_on_window(s_of_u) >= kMinTableSlope) {
          s.shape = Shape::bezier_table;
          tabulate_inverse(s, curve.inverse_);
        } else {
          s.shape = Shape::bezier_closed;
        }
        break;
      }
    }
    curve.segments_.push_back(s);
  }
  return curve;
}

// The inverse u(s) of a strictly increasing time cubic, as kTablePieces cubic Hermite pieces: on
// each equal interval of s a piece matches u and du/ds = 1 / s'(u) at both ends. Each piece is
// checked at build time at points across its interval and given the fewest refinement steps
// (0 to kMaxRefinements) that reach the residual there; a piece that does not (near an end where
// s'(u) is small the inverse bends too fast for a cubic) is filled with NaN, so that its samples
// always take Blender's closed form.
void Curve::tabulate_inverse(Segment& segment, std::vector<InversePiece>& table) {
  const Cubic s{0.0, segment.k1, segment.k2, segment.k3};
  constexpr int n = kTablePieces;
  double u[n + 1], du_dw[n + 1];
  for (int j = 0; j <= n; ++j) {
    u[j] = j == 0 ? 0.0 : j == n ? 1.0 : invert_increasing(s, static_cast<double>(j) / n);
    du_dw[j] = 1.0 / (s.slope_at(u[j]) * n);  // du/dw = du/ds * ds/dw, with ds/dw = 1 / n
  }
  segment.table = static_cast<std::uint32_t>(table.size());
  for (int j = 0; j < n; ++j) {
    const double m0 = du_dw[j], m1 = du_dw[j + 1], step = u[j + 1] - u[j];
    InversePiece piece{u[j], m0, 3.0 * step - 2.0 * m0 - m1, -2.0 * step + m0 + m1, 0};
    const auto reaches = [&] {
      constexpr int kChecks = 32;
      for (int k = 0; k <= kChecks; ++k) {
        const double w = static_cast<double>(k) / kChecks;
        double residual = 0;
        refine(segment, piece, w, (j + w) / n, residual);
        if (!(std::abs(residual) <= kMaxResidual / 4)) return false;
      }
      return true;
    };
    while (!reaches()) {
      if (++piece.refinements > kMaxRefinements) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        piece = {nan, nan, nan, nan, 0};
        break;
      }
    }
    table.push_back(piece);
  }
}

// From the table's estimate of u, steps u -= (s(u) - x) du/ds with du/ds also from the table:
// each step multiplies the error by about the table's relative error in du/ds, with no division.
// residual = s(u) - x at the returned u.
double Curve::refine(const Segment& s, const InversePiece& p, double w, double x, double& residual) noexcept {
  double u = p.a0 + w * (p.a1 + w * (p.a2 + w * p.a3));
  residual = u * (s.k1 + u * (s.k2 + u * s.k3)) - x;
  if (p.refinements > 0) {
    const double du_dx = (p.a1 + w * (2.0 * p.a2 + w * 3.0 * p.a3)) * kTablePieces;
    for (int i = 0; i < p.refinements; ++i) {
      u -= residual * du_dx;
      residual = u * (s.k1 + u * (s.k2 + u * s.k3)) - x;
    }
  }
  return u;
}

double Curve::evaluate_bezier_closed(const Segment& s, double x) const noexcept {
  // Blender returns a key's own value when the time falls on it, whatever roots the cubic has.
  if (x == 0.0) return s.v0;
  double roots[3];
  // x(u) - x with x(0) = 0 <= x < 1 = x(1) always has a root in [0, 1]; if rounding at the very
  // ends of the segment loses it, the linear estimate of u stands in (Blender would return 0).
  const double u = solve_cubic_in_unit_interval(-x, s.k1, s.k2, s.k3, roots) > 0 ? roots[0] : std::clamp(x, 0.0, 1.0);
  return s.v0 + u * (s.e1 + u * (s.e2 + u * s.e3));
}

double Curve::evaluate_in(std::size_t i, double t) const noexcept {
  const Segment& s = segments_[i];
  const double x = (t - s.t0) * s.inv_duration;  // in [0, 1]: the segment holds t
  switch (s.shape) {
    case Shape::step:
    case Shape::constant: return s.v0;
    case Shape::linear: return s.v0 + x * s.e1;
    case Shape::bezier_table: {
      const double scaled = x * kTablePieces;
      const int j = std::min(static_cast<int>(scaled), kTablePieces - 1);
      double residual = 0;
      const double u = refine(s, inverse_[s.table + static_cast<std::size_t>(j)], scaled - j, x, residual);
      // |u - root| <= |residual| / min s'(u) <= 1e-9; otherwise (a NaN piece) Blender's solve.
      if (!(std::abs(residual) <= kMaxResidual)) return evaluate_bezier_closed(s, x);
      return s.v0 + u * (s.e1 + u * (s.e2 + u * s.e3));
    }
    case Shape::bezier_closed: return evaluate_bezier_closed(s, x);
  }
  return s.v0;
}

std::size_t Curve::find_segment(double t) const noexcept {
  // The last key at or before t; callers guarantee times_.front() < t < times_.back().
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  return static_cast<std::size_t>(after - times_.begin()) - 1;
}

double Curve::evaluate(double t, CurveCursor& cursor) const noexcept {
  if (!(t > start_)) return first_value_;
  if (t >= end_) return last_value_;
  std::size_t i = cursor.segment;
  if (i >= segments_.size() || t < times_[i]) {
    i = find_segment(t);
  } else if (t >= times_[i + 1]) {
    // A few segments ahead are walked; further jumps search. t < end_ stops the walk in range.
    int steps = 0;
    do ++i;
    while (t >= times_[i + 1] && ++steps < 4);
    if (t >= times_[i + 1]) i = find_segment(t);
  }
  cursor.segment = i;
  return evaluate_in(i, t);
}

double Curve::evaluate(double t) const noexcept {
  if (!(t > start_)) return first_value_;
  if (t >= end_) return last_value_;
  return evaluate_in(find_segment(t), t);
}

}  // namespace avar::playback
