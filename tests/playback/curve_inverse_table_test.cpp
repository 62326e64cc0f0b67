// Bezier segments with free time handles, sampled densely: where time rises at least 0.1 segment
// per unit of the parameter (the tabulated inverse, its certified and its checked pieces), the
// parameter is within 1e-9 of the root, so the value is within 1e-9 times the largest |dv/du| of
// the exact one, from the segment's first instant to its last double; everywhere (Blender's solve
// where time nearly stalls too) sequential sampling gives the random access value bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "avar/playback/runtime/bezier_time_solve.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::build;
using testing::key;

// u in [0, 1] with s(u) = x, s increasing from 0 to 1 over [0, 1] (or nearly, where it stalls):
// bisection to the last bit.
double exact_parameter(const Cubic& s, double x) {
  double lo = 0, hi = 1;
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (s.at(mid) < x ? lo : hi) = mid;
  }
  return std::abs(s.at(lo) - x) <= std::abs(s.at(hi) - x) ? lo : hi;
}

TEST(CurveInverseTable, ParameterWithinItsBoundFromEndToEnd) {
  const unsigned seed = 31337;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  // Handle extents as fractions of the segment: 0.034 makes s'(0) = 0.102, just steep enough for
  // the table; 1.0 on both sides makes time nearly stall in the middle (Blender's solve).
  const double extents[] = {0.034, 0.04, 0.07, 0.15, 1.0 / 3, 0.5, 0.8, 1.0};
  for (double a : extents)
    for (double b : extents) {
      const double t0 = u(rng) < 0.5 ? 0.0 : 1000 * u(rng), d = std::pow(10.0, -2 + 5 * u(rng));
      const double v[4] = {-50 + 100 * u(rng), -50 + 100 * u(rng), -50 + 100 * u(rng), -50 + 100 * u(rng)};
      const double t1 = t0 + d;
      const Curve c = build({key(t0, v[0], Interpolation::bezier, {}, Handle{t0 + a * d, v[1]}),
                             key(t1, v[3], Interpolation::linear, Handle{t1 - b * d, v[2]})});
      const double unit_times[4] = {0, a, 1 - b, 1};
      const Cubic s = bezier_polynomial(unit_times);
      const double steepest = 3 * std::max({std::abs(v[1] - v[0]), std::abs(v[2] - v[1]), std::abs(v[3] - v[2])});
      double flattest = s.slope_at(0);
      for (int k = 1; k <= 1000; ++k) flattest = std::min(flattest, s.slope_at(k / 1000.0));
      std::vector<double> times;
      for (int k = 0; k <= 4000; ++k) times.push_back(t0 + d * k / 4000.0);
      for (double e : {1e-15, 1e-12, 1e-9, 1e-6}) times.push_back(t0 + e * d), times.push_back(t1 - e * d);
      times.push_back(std::nextafter(t1, t0));
      std::sort(times.begin(), times.end());
      CurveCursor cursor;
      for (double t : times) {
        if (!(t >= t0 && t < t1)) continue;
        const double x = (t - t0) / d;
        const double got = c.evaluate(t, cursor);
        // Within the key snap of either key, that key's value (the curve's only segment).
        if (t - t0 <= Curve::kKeySnap || t1 - t <= Curve::kKeySnap) {
          ASSERT_EQ(got, t - t0 <= Curve::kKeySnap ? v[0] : v[3]) << "handles " << a << ", " << b << " at x " << x;
          continue;
        }
        const double want = bezier_value(v, exact_parameter(s, x));
        if (flattest >= 0.1) {
          ASSERT_NEAR(got, want, 1e-9 * steepest + 1e-12) << "handles " << a << ", " << b << " at x " << x;
        }
        ASSERT_TRUE(std::isfinite(got)) << "handles " << a << ", " << b << " at x " << x;
        ASSERT_EQ(got, c.evaluate(t)) << "handles " << a << ", " << b << " at x " << x;
      }
    }
}

}  // namespace
}  // namespace avar::playback
