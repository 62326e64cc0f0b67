#pragma once
// D(vp): the distance of a plan's velocity change to vp and its stop from there, with D'.

#include <cmath>
#include <limits>

#include "jerk_stop.hpp"
#include "jerk_velocity_change.hpp"

namespace avar::control::jerk {

/// Distance of phase 1 (to vp) plus the stop from (vp, 0), and its slope d/dvp (change_slope()
/// plus stop_slope()).
struct Reach {
  double distance;
  double slope;
  double magnitude;       ///< the distance is exact to a few ulps of this
  double duration;        ///< of the change and the stop (s): the plan's, but for a cruise
  double stop_peak;       ///< |peak acceleration| of the stop, <= A
  VelocityChange change;  ///< phase 1
};

[[gnu::always_inline]] inline Reach reach(double v0, double a0, double vp, const Bounds& k) {
  Reach r;  // (every member is set below)
  r.change = velocity_change(v0, a0, vp, k);
  const VelocityChange& c = r.change;
  r.distance = c.distance;
  r.magnitude = c.magnitude;
  r.slope = c.peak > 0 ? change_slope(c.s, vp, c.peak, k) : std::numeric_limits<double>::infinity();
  // The stop from (vp, 0): peak m = sqrt(J|vp|) <= A, where |vp|/m = m/J (no division).
  const double speed = std::abs(vp);
  const double root = std::sqrt(k.J * speed);
  const bool reaches_a = root > k.A;
  const double m = reaches_a ? k.A : root;
  r.stop_peak = m;
  const double coast = stop_coast(speed, m, reaches_a, k);
  const double duration = m * k.inv_J + coast;
  r.distance += 0.5 * vp * duration;
  r.magnitude += speed * duration;
  r.duration = c.rise + c.hold + c.fall + duration;
  r.slope += stop_slope(coast, m, k);
  return r;
}

/// D'' at r (at vp): the change's plus the stop's.
inline double reach_curvature(const Reach& r, double vp, const Bounds& k) {
  const VelocityChange& c = r.change;
  return change_curvature(c.s, vp, c.peak, c.hold > 0, k) + stop_curvature(vp, r.stop_peak, k);
}

/// D''' at r (at vp): the change's plus the stop's.
inline double reach_third(const Reach& r, double vp, const Bounds& k) {
  const VelocityChange& c = r.change;
  return change_third(c.s, vp, c.peak, c.hold > 0, k) + stop_third(r.stop_peak, k);
}

}  // namespace avar::control::jerk
