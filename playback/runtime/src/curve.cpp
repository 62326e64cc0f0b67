#include "avar/playback/runtime/curve.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>

#include "avar/core/bit_cast.hpp"
#include "avar/playback/runtime/bezier_time_solve.hpp"
#include "avar/playback/runtime/easing.hpp"

namespace avar::playback {
namespace {

double finite_or(double x, double fallback) noexcept { return std::isfinite(x) ? x : fallback; }

}  // namespace

// From the piece's estimate of u, steps u -= (s(u) - x) du/dx with du/dx also from the piece:
// each step multiplies the error by about the piece's relative error in du/dx, with no division.
// A u is taken once it lies in Blender's window with |s(u) - x| <= kMaxResidual; that is the
// certificate here, checked on every sample.
double Curve::evaluate_uncertified(const Segment& s, const InversePiece& p, double w, double scaled) const noexcept {
  const auto b = avar::bit_cast<TableHeader>(inverse_[s.extra - 1]);
  const double pieces = b.pieces;
  const double x = scaled / pieces;  // exact: a power of two
  const InversePiece q{p.a0, -p.a1, p.a2, p.a3, p.a4, p.a5};
  const auto residual_at = [&](double u) { return (u * b.k1 - x) + (u * u) * (b.k2 + u * b.k3); };
  const double w2 = w * w;
  const double du_dx = ((q.a1 + w * (2.0 * q.a2)) + w2 * ((3.0 * q.a3 + w * (4.0 * q.a4)) + w2 * (5.0 * q.a5))) * pieces;
  double u = q.at(w);
  double residual = residual_at(u);
  for (int step = 0; !(std::abs(residual) <= kMaxResidual && u >= kWindowLow && u <= kWindowHigh); ++step) {
    if (step == kMaxRefinements) return evaluate_bezier_closed(s, b.k1, b.k2, b.k3, x);
    u -= residual * du_dx;
    residual = residual_at(u);
  }
  return value_cubic(s, u);
}

double Curve::evaluate_bezier_closed(const Segment& s, double k1, double k2, double k3, double normalised_time) noexcept {
  const double x = normalised_time;
  // Blender returns a key's own value when the time falls on it, whatever roots the cubic has.
  if (x == 0.0) return s.v0;
  double roots[3];
  // x(u) - x with x(0) = 0 <= x < 1 = x(1) always has a root in [0, 1]; if rounding at the very
  // ends of the segment loses it, the linear estimate of u stands in (Blender would return 0).
  const double u = solve_cubic_in_unit_interval(-x, k1, k2, k3, roots) > 0 ? roots[0] : std::clamp(x, 0.0, 1.0);
  return value_cubic(s, u);
}

double Curve::evaluate_solved(const Segment& s, double x, double t) const noexcept {
  switch (s.shape) {
    case Shape::linear:
    case Shape::polynomial:
    case Shape::bezier_table: break;  // evaluate_in's (linear: e2 = e3 = 0)
    case Shape::bezier_closed: {
      const SegmentExtra& b = extras_[s.extra];
      return evaluate_bezier_closed(s, b.k1, b.k2, b.k3, x);
    }
    case Shape::easing: {
      const SegmentExtra& b = extras_[s.extra];
      const double duration = 1.0 / s.inv_duration;
      return ease(s.family, s.easing, t - s.t0, s.v0, s.e1, duration, EasingParams{b.k1, b.k2, b.k3});
    }
  }
  return value_cubic(s, x);
}

std::size_t Curve::find_segment(double t) const noexcept {
  // The last key at or before t; callers guarantee times_.front() < t < times_.back().
  const double* after = std::upper_bound(times_, times_ + key_count_, t);
  return static_cast<std::size_t>(after - times_) - 1;
}

double Curve::extrapolate(double t) const noexcept {
  const bool before = !(t > start_);
  const double value = before ? first_value_ : last_value_;
  const double slope = before ? slope_before_ : slope_after_;
  if (slope == 0 || !std::isfinite(t)) return value;
  const double result = value + slope * (t - (before ? start_ : end_));
  return std::clamp(finite_or(result, value), -DBL_MAX, DBL_MAX);
}

// Blender's fcm_cycles_time, in doubles: map t outside the keys into them, cycle by cycle.
double Curve::cycle_time(double t, double& offset) const noexcept {
  offset = 0;
  int side = 0;
  CycleMode mode = CycleMode::none;
  int count = 0;
  double from = 0;
  if (t < start_ && cycles_.before != CycleMode::none) {
    side = -1, mode = cycles_.before, count = cycles_.before_count, from = start_;
  } else if (t > end_ && cycles_.after != CycleMode::none) {
    side = 1, mode = cycles_.after, count = cycles_.after_count, from = end_;
  }
  const double dx = end_ - start_;
  if (side == 0 || dx == 0 || !std::isfinite(t)) return t;
  // Blender works in frames, where cycle boundaries fall on exact numbers; in seconds they carry
  // rounding, so a time within 1e-9 cycles of a boundary counts as on it.
  double cycle = side * (t - from) / dx;  // >= 0
  const double nearest = std::round(cycle);
  const bool on_boundary = std::abs(cycle - nearest) <= 1e-9 * std::max(1.0, nearest);
  if (on_boundary) cycle = nearest;
  const double within = on_boundary ? 0.0 : std::fmod(t - from, dx);
  if (count != 0 && cycle > count) return t;
  if (mode == CycleMode::repeat_offset) {
    const double signed_cycles = side * cycle;
    const double whole = side < 0 ? std::floor(signed_cycles) : std::ceil(signed_cycles);
    offset = whole * (last_value_ - first_value_);
  }
  const auto odd = [](double c) { return std::fmod(std::floor(c), 2.0) == 1.0; };
  double mapped;
  if (within == 0) {
    mapped = side == 1 ? end_ : start_;
    if (mode == CycleMode::mirror && odd(cycle)) mapped = side == 1 ? start_ : end_;
  } else if (mode == CycleMode::mirror && odd(cycle + 1)) {
    mapped = (side < 0 ? start_ : end_) - within;
  } else {
    mapped = start_ + within;
  }
  if (mapped < start_) mapped += dx;
  return mapped;
}

double Curve::snapped_to_ends(double t) const noexcept {
  if (std::abs(t - start_) <= kKeySnap) return start_;
  if (std::abs(t - end_) <= kKeySnap) return end_;
  return t;
}

double Curve::evaluate_keys(double t, CurveCursor* cursor) const noexcept {
  t = snapped_to_ends(t);  // a cycled time may land there
  if (!(t > start_) || t >= end_) return extrapolate(t);
  std::size_t i = cursor ? cursor->segment : segment_count_;
  if (i >= segment_count_ || t < times_[i]) {
    // (A looping show comes back to the first segment: no search for it.)
    i = t < times_[1] ? 0 : find_segment(t);
  } else if (t >= times_[i + 1]) {
    // A few segments ahead are walked; further jumps search. t < end_ stops the walk in range.
    int steps = 0;
    do ++i;
    while (t >= times_[i + 1] && ++steps < 4);
    if (t >= times_[i + 1]) i = find_segment(t);
  }
  // Within kKeySnap of one of the segment's keys: that key's time (the nearer one, should the
  // keys be closer than twice the snap). The key that ends the segment starts the next one.
  const double after_start = t - times_[i], before_end = times_[i + 1] - t;
  if (before_end <= kKeySnap && before_end < after_start) {
    t = times_[++i];
    if (i == segment_count_) return extrapolate(t);  // not reached: the last key snapped above
  } else if (after_start <= kKeySnap) {
    t = times_[i];
  }
  if (cursor) cursor->segment = i;
  return evaluate_in(segments_[i], t);
}

double Curve::warm(const CurveCursor& cursor) const noexcept {
  if (segment_count_ == 0) return first_value_;
  const std::size_t here = cursor.segment < segment_count_ ? cursor.segment : 0;
  const std::size_t next = here + 1 < segment_count_ ? here + 1 : 0;
  double sum = first_value_;
  for (const std::size_t i : {here, next}) {
    const Segment& s = segments_[i];
    sum += s.v0 + times_[i + 1];
    if (s.shape == Shape::bezier_table) {
      // A piece is 48 bytes and may straddle two cache lines: its first and last coefficients.
      const InversePiece& p = inverse_[s.extra];
      sum += p.a0 + p.a5;
    } else if (s.shape == Shape::bezier_closed || s.shape == Shape::easing) {
      sum += extras_[s.extra].k1;
    }
  }
  return sum;
}

// Key times themselves come here too: the general path decides which segment owns them.
double Curve::evaluate_moved(double t, CurveCursor& cursor) const noexcept {
  if (key_count_ == 0) return 0;
  if (!cycles_.any()) return evaluate_keys(t, &cursor);  // it snaps t to the keys
  t = snapped_to_ends(t);                                // before the cycle map: the end key, not the next cycle
  if (t >= start_ && t <= end_) return evaluate_keys(t, &cursor);
  double offset = 0;
  const double mapped = cycle_time(t, offset);
  const double base = evaluate_keys(mapped, &cursor);
  return std::clamp(finite_or(base + offset, base), -DBL_MAX, DBL_MAX);
}

double Curve::evaluate(double t) const noexcept {
  if (key_count_ == 0) return 0;
  if (!cycles_.any()) return evaluate_keys(t, nullptr);  // it snaps t to the keys
  t = snapped_to_ends(t);                                // before the cycle map: the end key, not the next cycle
  if (t >= start_ && t <= end_) return evaluate_keys(t, nullptr);
  double offset = 0;
  const double mapped = cycle_time(t, offset);
  const double base = evaluate_keys(mapped, nullptr);
  return std::clamp(finite_or(base + offset, base), -DBL_MAX, DBL_MAX);
}

Curve::SegmentView Curve::segment_view(std::size_t i) const noexcept {
  const Segment& s = segments_[i];
  SegmentView v;
  v.t0 = s.t0, v.t1 = s.t1;
  v.v0 = s.v0, v.e1 = s.e1, v.e2 = s.e2, v.e3 = s.e3;
  switch (s.shape) {
    case Shape::linear: v.kind = s.e1 == 0 ? SegmentView::Kind::constant : SegmentView::Kind::linear; break;
    case Shape::polynomial: v.kind = SegmentView::Kind::cubic; break;
    case Shape::bezier_table: {
      const auto b = avar::bit_cast<TableHeader>(inverse_[s.extra - 1]);
      v.kind = SegmentView::Kind::bezier;
      v.k1 = b.k1, v.k2 = b.k2, v.k3 = b.k3;
      break;
    }
    case Shape::bezier_closed: {
      const SegmentExtra& b = extras_[s.extra];
      v.kind = SegmentView::Kind::bezier;
      v.k1 = b.k1, v.k2 = b.k2, v.k3 = b.k3;
      break;
    }
    case Shape::easing: {
      const SegmentExtra& b = extras_[s.extra];
      v.kind = SegmentView::Kind::easing;
      v.family = s.family;
      v.easing = s.easing;
      v.back = b.k1, v.amplitude = b.k2, v.period = b.k3;
      break;
    }
  }
  return v;
}

void Curve::adopt(Tables tables) {
  auto shared = std::make_shared<const Tables>(std::move(tables));
  times_ = shared->times.data();
  segments_ = shared->segments.data();
  extras_ = shared->extras.data();
  inverse_ = shared->inverse.data();
  key_count_ = shared->times.size();
  segment_count_ = shared->segments.size();
  tables_ = std::move(shared);
}

}  // namespace avar::playback
