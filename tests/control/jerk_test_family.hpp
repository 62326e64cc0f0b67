#pragma once
// A seeded family of limits, starts and goals for the jerk-limited solve's stage tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <random>
#include <string>
#include <utility>

#include "avar/control/jerk_profile.hpp"

namespace avar::control::jerk::testing {

/// (f(x + h) - f(x - h)) / 2h.
template <class F>
double central_difference(const F& f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2 * h);
}

/// The state after constant-jerk pieces {duration (s), jerk} from s.
inline MotionState run_pieces(MotionState s, std::initializer_list<std::pair<double, double>> pieces) {
  for (const auto& [t, j] : pieces) {
    s.p += t * (s.v + t * (s.a / 2 + t * j / 6));
    s.v += t * (s.a + t * j / 2);
    s.a += t * j;
  }
  return s;
}

/// One draw of the family: limits, a start and a peak velocity within [-V, V].
struct JerkCase {
  JerkLimits limits;
  MotionState start;
  double vp;
};

/// Limits log-uniform over V in [0.1, 500], A in [1, 5000], J in [10, 1e5]; starts with
/// |v| <= V and |a| <= A that can keep |v| <= V. Failures name the seed (SCOPED_TRACE).
class JerkFamily {
 public:
  explicit JerkFamily(unsigned seed) : rng_(seed), trace_(__FILE__, __LINE__, "seed " + std::to_string(seed)) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform(0, 1)); }
  double sign() { return uniform(0, 1) < 0.5 ? -1.0 : 1.0; }

  JerkLimits limits() { return {log_uniform(0.1, 500), log_uniform(1, 5000), log_uniform(10, 1e5)}; }
  /// A start within the limits whose natural velocity v + a|a|/(2J) is within [-V, V].
  MotionState start(const JerkLimits& l) {
    MotionState s;
    s.p = uniform(-50, 50);
    s.a = uniform(-l.acceleration, l.acceleration);
    const double release = 0.5 * s.a * std::abs(s.a) / l.jerk;
    s.v = std::clamp(uniform(-l.velocity, l.velocity) - release, -l.velocity, l.velocity);
    if (std::abs(s.v + release) > l.velocity) s.v = -release;
    return s;
  }
  JerkCase draw() {
    JerkCase c;
    c.limits = limits();
    c.start = start(c.limits);
    c.vp = uniform(-c.limits.velocity, c.limits.velocity);
    return c;
  }
  /// A goal from 1e-6 to 100 units away.
  double goal(const MotionState& s) { return s.p + sign() * log_uniform(1e-6, 100); }

 private:
  std::mt19937_64 rng_;
  ::testing::ScopedTrace trace_;
};

}  // namespace avar::control::jerk::testing
