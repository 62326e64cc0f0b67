#pragma once
// Taylor estimates of D around an evaluation: what a step is left with, unevaluated.

#include <cmath>
#include <limits>

#include "jerk_reach.hpp"

namespace avar::control::jerk {

/// Whether a step of `step` from r (at vp) stays well inside r's regimes, where D is smooth and
/// its derivatives change by a few percent at most: each phase's peak acceleration squared moves
/// by under 1% (J |step| of it), without reaching A or the change's start acceleration, a hold
/// stays, the stop's velocity keeps its sign.
inline bool stays_inside(const Reach& r, double vp, double step, const Bounds& k) {
  const double jump = k.J * std::abs(step);  // how far the peaks' squares move
  const VelocityChange& c = r.change;
  const double b0 = c.peak - c.rise * k.J;  // the change's start acceleration, in its frame
  if (c.hold > 0) {
    if (!(std::abs(step) < 0.5 * c.hold * k.A)) return false;
  } else {
    const double m2 = c.peak * c.peak;
    // (A change that starts against its direction, b0 <= 0, rises through zero to any m > 0.)
    if (!(jump <= 0.01 * m2 && 2 * jump < k.A * k.A - m2 && (b0 <= 0 || 2 * jump < m2 - b0 * b0))) return false;
  }
  const double m = r.stop_peak, m2 = m * m;
  if (m2 >= k.A * k.A) return 2 * jump < k.J * std::abs(vp) - k.A * k.A;
  return jump <= 0.01 * m2 && 2 * jump < k.A * k.A - m2;
}

/// The residual a step of `step` from r (at vp) is left with, by Taylor: r + D' step + D'' step²/2.
/// (After a Newton step in vp, D'' step²/2; a step taken in sqrt(|vp - natural|) also leaves
/// part of the linear term.) NaN unless the step stays inside r's regimes (stays_inside).
inline double newton_residual(const Reach& r, double vp, double step, const Bounds& k) {
  if (!stays_inside(r, vp, step, k)) return std::numeric_limits<double>::quiet_NaN();
  const double curvature = reach_curvature(r, vp, k);
  return r.distance + r.slope * step + 0.5 * curvature * step * step;
}

/// A second-order step from r (at vp): the root of r + D' x + D'' x²/2 next to 0, with the
/// residual it is left with by Taylor, D''' x³/6; NaN where the step leaves r's regimes
/// (stays_inside) or the quadratic has no real root.
struct SecondOrderStep {
  double step, residual;
};
inline SecondOrderStep second_order_step(const Reach& r, double vp, const Bounds& k) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double curvature = reach_curvature(r, vp, k);
  const double discriminant = r.slope * r.slope - 2 * curvature * r.distance;
  if (!(discriminant > 0)) return {nan, nan};
  const double step = -2 * r.distance / (r.slope + std::sqrt(discriminant));
  if (!stays_inside(r, vp, step, k)) return {nan, nan};
  const double third = reach_third(r, vp, k);
  return {step, third * step * step * step / 6};
}

}  // namespace avar::control::jerk
