#include "avar/core/format.hpp"
#include "avar/playback/curve.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "avar/playback/bezier_time_solve.hpp"

namespace avar::playback {
namespace {

/// Blender's BKE_fcurve_correct_bezpart: neither handle may reach further in time than the
/// segment is long; a longer one is shortened, keeping its direction.
void correct_handles(double tx[4], double vy[4]) {
  const double len = tx[3] - tx[0];
  const double h1t = tx[0] - tx[1], h1v = vy[0] - vy[1];
  const double h2t = tx[3] - tx[2], h2v = vy[3] - vy[2];
  const double len1 = std::abs(h1t), len2 = std::abs(h2t);
  if (len1 + len2 == 0.0) return;
  if (len1 > len) {
    const double fac = len / len1;
    tx[1] = tx[0] - fac * h1t;
    vy[1] = vy[0] - fac * h1v;
  }
  if (len2 > len) {
    const double fac = len / len2;
    tx[2] = tx[3] - fac * h2t;
    vy[2] = vy[3] - fac * h2v;
  }
}

}  // namespace

std::optional<Interpolation> interpolation_from_name(std::string_view name) {
  if (name == "step") return Interpolation::step;
  if (name == "linear") return Interpolation::linear;
  if (name == "bezier") return Interpolation::bezier;
  return std::nullopt;
}

const char* to_string(Interpolation i) {
  switch (i) {
    case Interpolation::step: return "step";
    case Interpolation::linear: return "linear";
    case Interpolation::bezier: return "bezier";
  }
  return "unknown";
}

Curve Curve::build(const RawCurve& raw) {
  if (raw.keys.empty()) throw InputError(raw.where, "a track needs at least one key");
  Curve curve;
  curve.segments_.reserve(raw.keys.size());
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    if (!std::isfinite(k.time)) throw InputError(k.where, "key time " + format_number(k.time) + " is not a finite number of seconds");
    if (!std::isfinite(k.value)) throw InputError(k.where, "key value " + format_number(k.value) + " is not a finite number");
    if (i > 0 && !(k.time > raw.keys[i - 1].time))
      throw InputError(k.where, "key time " + format_number(k.time) + " s is not after the previous key's " +
                                    format_number(raw.keys[i - 1].time) + " s; key times must strictly increase");
    for (const auto* h : {&k.left, &k.right})
      if (*h && (!std::isfinite((*h)->time) || !std::isfinite((*h)->value)))
        throw InputError(k.where, "a handle of the key at " + format_number(k.time) + " s is not a pair of finite numbers");
  }
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const RawKey& k = raw.keys[i];
    Segment s;
    s.t0 = k.time;
    s.v0 = k.value;
    s.interpolation = k.interpolation;
    s.t1 = k.time;
    s.v1 = k.value;
    if (i + 1 < raw.keys.size()) {
      const RawKey& next = raw.keys[i + 1];
      s.t1 = next.time;
      s.v1 = next.value;
      if (k.interpolation == Interpolation::bezier) {
        if (!k.right)
          throw InputError(k.where, "the key at " + format_number(k.time) +
                                        " s starts a bezier segment and needs a right handle: right: [time, value]");
        if (!next.left)
          throw InputError(next.where, "the key at " + format_number(next.time) +
                                           " s ends a bezier segment and needs a left handle: left: [time, value]");
        s.tx[0] = k.time, s.tx[1] = k.right->time, s.tx[2] = next.left->time, s.tx[3] = next.time;
        s.vy[0] = k.value, s.vy[1] = k.right->value, s.vy[2] = next.left->value, s.vy[3] = next.value;
        // Blender short-cuts segments whose four values agree (to float precision).
        s.flat = std::abs(s.vy[0] - s.vy[3]) < FLT_EPSILON && std::abs(s.vy[1] - s.vy[2]) < FLT_EPSILON &&
                 std::abs(s.vy[2] - s.vy[3]) < FLT_EPSILON;
        correct_handles(s.tx, s.vy);
      }
    }
    curve.segments_.push_back(s);
  }
  return curve;
}

double Curve::evaluate_segment(const Segment& s, double t) const noexcept {
  switch (s.interpolation) {
    case Interpolation::step: return s.v0;
    case Interpolation::linear: return s.v0 + (t - s.t0) / (s.t1 - s.t0) * (s.v1 - s.v0);
    case Interpolation::bezier: {
      if (s.flat) return s.v0;
      double u = bezier_parameter_at_time(t, s.tx);
      // With corrected handles a root always exists; rounding at the very ends of a segment
      // can still lose it, and then the linear estimate of the parameter is used.
      if (u < 0) u = std::clamp((t - s.t0) / (s.t1 - s.t0), 0.0, 1.0);
      return bezier_value(s.vy, u);
    }
  }
  return s.v0;
}

std::size_t Curve::find_segment(double t) const noexcept {
  // Last segment whose start is <= t (the first if t is before every key).
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t, [](double x, const Segment& s) { return x < s.t0; });
  return it == segments_.begin() ? 0 : static_cast<std::size_t>(it - segments_.begin()) - 1;
}

double Curve::evaluate(double t, CurveCursor& cursor) const noexcept {
  const std::size_t last = segments_.size() - 1;
  if (t <= segments_.front().t0) return segments_.front().v0;
  if (t >= segments_[last].t0) return segments_[last].v0;
  std::size_t i = cursor.segment < last ? cursor.segment : 0;
  if (t < segments_[i].t0) {
    i = find_segment(t);
  } else {
    // Walk forward a few segments; jump by binary search when far ahead.
    int steps = 0;
    while (t >= segments_[i].t1 && ++steps < 4) ++i;
    if (t >= segments_[i].t1) i = find_segment(t);
  }
  cursor.segment = i;
  return evaluate_segment(segments_[i], t);
}

double Curve::evaluate(double t) const noexcept {
  CurveCursor cursor{find_segment(t)};
  return evaluate(t, cursor);
}

}  // namespace avar::playback
