#pragma once
// Phase 1 of a plan: the time-optimal velocity change from (v0, a0) to (v1, 0), its distance and
// the distance's derivatives in v1.

#include <algorithm>
#include <cmath>

#include "jerk_bounds.hpp"

namespace avar::control::jerk {

/// The time-optimal change from (v0, a0) to (v1, 0) with |a| <= A: jerk s·J until the
/// acceleration reaches s·peak, a hold there (only at peak = A), jerk -s·J back to zero.
/// (No member initialisers here and in Reach: the solve keeps one of each per plan and zeroing
/// them each time was a measurable part of a plan's cost; `{}` value-initialises.)
struct VelocityChange {
  double s;          ///< +1 raises the velocity past its natural value v0 + a0|a0|/(2J), -1 lowers it
  double peak;       ///< |peak acceleration|, <= A
  double rise;       ///< s (duration of the first jerk piece)
  double hold;       ///< s
  double fall;       ///< s
  double distance;   ///< units
  double magnitude;  ///< sum of the distance's terms' magnitudes: its rounding is a few ulps of this
};

// (Inlined into the solve's evaluation, as reach() is: 5% off a plan in interleaved replays of
// the bench's costliest tick.)
[[gnu::always_inline]] inline VelocityChange velocity_change(double v0, double a0, double v1, const Bounds& k) {
  constexpr double kSixth = 1.0 / 6;
  const double A = k.A, J = k.J;
  VelocityChange c;
  c.s = v1 >= v0 + 0.5 * a0 * std::abs(a0) * k.inv_J ? 1.0 : -1.0;
  // In the frame where the change raises the velocity: w = s v, b = s a.
  const double b0 = c.s * a0;
  const double w0 = c.s * v0;
  const double dw = c.s * (v1 - v0);
  // Velocity gained: (peak² - b0²)/(2J) rising, peak·hold, peak²/(2J) falling.
  const double peak_squared = std::max(0.0, J * dw + 0.5 * b0 * b0);
  if (peak_squared <= A * A) {
    c.peak = std::sqrt(peak_squared);
    c.hold = 0;
  } else {
    c.peak = A;
    c.hold = std::max(0.0, (dw - 0.5 * (2 * A * A - b0 * b0) * k.inv_J) * k.inv_A);
  }
  // peak >= b0 but for rounding, which would leave the change ending with a != 0.
  c.peak = std::max(c.peak, b0);
  c.rise = (c.peak - b0) * k.inv_J;
  c.fall = c.peak * k.inv_J;
  const double t1 = c.rise, t2 = c.hold, t3 = c.fall, m = c.peak;
  double w = w0;
  double x = t1 * (w + t1 * (0.5 * b0 + kSixth * J * t1));
  w += t1 * (b0 + 0.5 * J * t1);
  x += t2 * (w + 0.5 * m * t2);
  w += m * t2;
  x += t3 * (w + t3 * (0.5 * m - kSixth * J * t3));
  c.distance = c.s * x;
  const double t = t1 + t2 + t3;
  c.magnitude = (std::abs(w0) + m * t) * t;
  return c;
}

/// D' of a change to vp in direction s whose peak acceleration is m > 0: for a change to v1,
/// d distance/d v1 = s v1/m + m/(2J).
[[gnu::always_inline]] inline double change_slope(double s, double vp, double m, const Bounds& k) {
  return s * vp / m + 0.5 * m * k.inv_J;
}

/// D'' of the change: with peak acceleration m < A (m² = J s (vp - v0) + b0²/2)
/// 5s/(4m) - J vp/(2m³); one that holds at A has s/A.
inline double change_curvature(double s, double vp, double m, bool holds, const Bounds& k) {
  const double inv_m = 1 / m;
  return holds ? s * k.inv_A : (1.25 * s - 0.5 * k.J * vp * inv_m * inv_m) * inv_m;
}

/// D''' of the change, from its D'' (dm/dvp = J s/(2m) below A; D'' is constant where the peak is
/// at A): without hold -9J/(8m³) + 3J² s vp/(4m⁵).
inline double change_third(double s, double vp, double m, bool holds, const Bounds& k) {
  if (holds) return 0;
  const double inv_m = 1 / m, inv_m3 = inv_m * inv_m * inv_m;
  return (-1.125 + 0.75 * k.J * s * vp * inv_m * inv_m) * k.J * inv_m3;
}

}  // namespace avar::control::jerk
