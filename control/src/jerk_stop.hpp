#pragma once
// Phase 3 of a plan: the time-optimal stop from (vp, 0) to rest, and its distance's derivatives
// in vp. It covers vp T/2 in T = m/J + |vp|/m, with peak acceleration m = sqrt(J|vp|) <= A.

#include <algorithm>
#include <cmath>

#include "jerk_bounds.hpp"

namespace avar::control::jerk {

/// The peak acceleration of the time-optimal stop from (v, 0): sqrt(J|v|), at most A.
inline double stop_peak(double v, const Bounds& k) { return std::min(std::sqrt(k.J * std::abs(v)), k.A); }

/// |vp| / m for the stop from vp with peak acceleration m: |vp| / A where it reaches A, else
/// m / J (where m = sqrt(J |vp|), no division).
[[gnu::always_inline]] inline double stop_coast(double speed, double m, bool reaches_a, const Bounds& k) {
  return reaches_a ? speed * k.inv_A : m * k.inv_J;
}

/// D' of the stop from vp: it covers vp T/2 with T = m/J + |vp|/m.
[[gnu::always_inline]] inline double stop_slope(double coast, double m, const Bounds& k) { return coast + 0.5 * m * k.inv_J; }

/// D'' of the stop: with peak m < A 3 sign(vp)/(4m); one that reaches A has sign(vp)/A.
inline double stop_curvature(double vp, double m, const Bounds& k) {
  const double sign = vp > 0 ? 1.0 : -1.0;
  return m >= k.A ? sign * k.inv_A : 0.75 * sign / m;
}

/// D''' of the stop (dm/dvp = J sign(vp)/(2m) below A): -3J/(8m³) below A, else 0.
inline double stop_third(double m, const Bounds& k) { return m >= k.A ? 0.0 : -0.375 * k.J / (m * m * m); }

}  // namespace avar::control::jerk
