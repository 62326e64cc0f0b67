#pragma once
// Where D's branches meet: 0 and the natural velocity, and D's square-root corner at the latter.

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "jerk_bounds.hpp"

namespace avar::control::jerk {

/// D is increasing for vp beyond both the natural velocity (reached by releasing the
/// acceleration; computed exactly as velocity_change computes it) and 0; between them (a change
/// and a stop in the same direction) it may not be.
struct Branches {
  double a0;         ///< the start's acceleration, within [-A, A]
  double natural;    ///< v0 + a0|a0|/(2J) within [-V, V]; 0 where that is zero to rounding
  double low, high;  ///< min and max of 0 and natural
  /// Beyond the natural velocity, away from 0, where reaching vp means reversing the
  /// acceleration (the side where D has its square-root corner), D is smooth in
  /// u = sqrt(|vp - natural|) with slope corner_slope at u = 0: there vp = natural ± (r/slope)².
  double corner_slope;
  bool corner_beyond;  ///< that side exists (natural != 0)

  Branches(double v0, double a0_, double V, const Bounds& k) : a0(a0_) {
    // A natural velocity that is zero to rounding (a state braking onto rest) is zero: the two
    // branch ends coincide, and the solve next to them runs in u (below) rather than creeping up
    // on a |vp|^(3/2) root in vp.
    const double release = 0.5 * a0 * std::abs(a0) * k.inv_J;
    const double unsnapped = std::clamp(v0 + release, -V, V);
    natural = std::abs(unsnapped) <= 8 * DBL_EPSILON * std::abs(v0) ? 0.0 : unsnapped;
    low = std::min(natural, 0.0), high = std::max(natural, 0.0);
    corner_slope = 2 * natural * std::sqrt(k.inv_J);
    corner_beyond = natural != 0 && (natural > 0 ? a0 <= 0 : a0 >= 0);
  }

  /// Whether the branch [lo, hi] starts at the natural velocity on the corner's side: D grows
  /// like sqrt(|vp - natural|) there, and Newton runs in u = sqrt(|vp - natural|), where D is
  /// smooth.
  bool cornered(double lo, double hi) const { return (lo == natural && a0 <= 0) || (hi == natural && a0 >= 0); }
};

/// The variable the solve runs in on a branch: u = sqrt(|vp - natural|) where `mapped` (dir: +1
/// when the branch lies above the natural velocity, -1 below), else vp itself.
struct CornerMap {
  bool mapped;
  double natural, dir;
  double to_vp(double u) const { return mapped ? natural + dir * u * u : u; }
  double to_u(double x) const { return mapped ? std::sqrt(std::abs(x - natural)) : x; }
  /// dD/du from dD/dvp at u.
  double slope(double slope_vp, double u) const { return mapped ? slope_vp * 2 * u * dir : slope_vp; }
};

}  // namespace avar::control::jerk
