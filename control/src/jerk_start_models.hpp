#pragma once
// Where the root of D(vp) = d lies by a model, from a branch end: the solve's first guesses when
// the peak jumps (a goal that stops or turns back).

#include <algorithm>
#include <cmath>
#include <limits>

#include "jerk_branches.hpp"
#include "jerk_reach.hpp"

namespace avar::control::jerk {

/// The braking model from r at 0 (brake to rest first): the braking change's distance is smooth in
/// vp there (slope r.slope, the change's peak acceleration staying well away from 0) and the stop
/// from vp adds vp sqrt(|vp|/J): with vp = -sign(r) y², y solves sqrt(1/J) y³ + slope y² = |r|,
/// by Newton from above (convex: monotone, 3 steps suffice for a start). NaN where it does not
/// apply (a start at rest, a root beyond its range).
inline double braking_model(const Branches& b, const Reach& r, const Bounds& bounds) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (b.natural == 0 || !(r.slope > 0) || !std::isfinite(r.slope)) return nan;
  const double target = std::abs(r.distance), k = std::sqrt(bounds.inv_J);
  // The change is linear only while J |vp| stays small next to its peak acceleration squared:
  // y up to y_valid. A root beyond that is left to the move from rest.
  const double y_valid = 0.5 * r.change.peak * k;
  if (y_valid * y_valid * (k * y_valid + r.slope) < target) return nan;
  // y_valid and the quadratic term alone both bound y from above.
  double y = std::min(y_valid, std::sqrt(target / r.slope));
  for (int i = 0; i < 3 && y > 0; ++i) y -= (y * y * (k * y + r.slope) - target) / (y * (3 * k * y + 2 * r.slope));
  return r.distance > 0 ? -y * y : y * y;
}

/// Where the root lies by a model, from a branch end `end` (0 or the natural velocity) with
/// residual r there; `beyond`: the root lies on the far side of `end` from 0 (the corner model,
/// Branches::corner_slope, when it applies). From the natural velocity (release the
/// acceleration), or from 0 when the start is at rest, the rest of the distance is a move from
/// rest: rest_to_rest_peak, exact from rest. From 0 otherwise, the braking model.
inline double model_from(const Branches& b, double end, const Reach& r, bool beyond, const JerkLimits& limits,
                         const Bounds& bounds) {
  const double natural = b.natural;
  if (end == natural && beyond && b.corner_beyond) {
    const double u = -r.distance / b.corner_slope;
    if (u > 0) return natural + (natural > 0 ? u * u : -u * u);
  }
  const double braking = end == 0 ? braking_model(b, r, bounds) : std::numeric_limits<double>::quiet_NaN();
  return braking == braking ? braking : end + rest_to_rest_peak(-r.distance, limits);
}

}  // namespace avar::control::jerk
