#pragma once
// The limits of the jerk-limited solve with the reciprocals its hot stages multiply by.

#include "avar/control/jerk_profile.hpp"

namespace avar::control::jerk {

/// The acceleration and jerk limits with their reciprocals (the solve evaluates D several times
/// per plan; multiplications are much cheaper than divisions).
struct Bounds {
  double A, J, inv_A, inv_J;
  explicit Bounds(const JerkLimits& l) : A(l.acceleration), J(l.jerk), inv_A(1 / l.acceleration), inv_J(1 / l.jerk) {}
  /// With the reciprocals already known.
  Bounds(const JerkLimits& l, double inverse_a, double inverse_j)
      : A(l.acceleration), J(l.jerk), inv_A(inverse_a), inv_J(inverse_j) {}
};

}  // namespace avar::control::jerk
