#include "avar/playback/bezier_time_solve.hpp"

#include <cmath>

namespace avar::playback {
namespace {

constexpr double kLow = -1.0e-10;    // Blender's SMALL
constexpr double kHigh = 1.000001;

bool in_range(double u) noexcept { return u >= kLow && u <= kHigh; }

}  // namespace

int solve_cubic_in_unit_interval(double c0, double c1, double c2, double c3, double roots[3]) noexcept {
  int n = 0;
  if (c3 != 0.0) {
    // Depressed cubic t^3 + p t + q = 0 after u = t - a, with Cardano for one real root and
    // the trigonometric form for three.
    double a = c2 / c3;
    const double b = c1 / c3;
    const double c = c0 / c3;
    a /= 3.0;
    const double p = b / 3.0 - a * a;
    const double q = (2.0 * a * a * a - a * b + c) / 2.0;
    const double d = q * q + p * p * p;
    if (d > 0.0) {
      const double t = std::sqrt(d);
      roots[0] = std::cbrt(-q + t) + std::cbrt(-q - t) - a;
      return in_range(roots[0]) ? 1 : 0;
    }
    if (d == 0.0) {
      const double t = std::cbrt(-q);
      roots[0] = 2.0 * t - a;
      if (in_range(roots[0])) ++n;
      roots[n] = -t - a;
      return in_range(roots[n]) ? n + 1 : n;
    }
    const double phi = std::acos(-q / std::sqrt(-(p * p * p)));
    const double t = std::sqrt(-p);
    const double cp = std::cos(phi / 3.0);
    const double sq = std::sqrt(3.0 - 3.0 * cp * cp);
    roots[0] = 2.0 * t * cp - a;
    if (in_range(roots[0])) ++n;
    roots[n] = -t * (cp + sq) - a;
    if (in_range(roots[n])) ++n;
    roots[n] = -t * (cp - sq) - a;
    return in_range(roots[n]) ? n + 1 : n;
  }
  if (c2 != 0.0) {
    double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc > 0.0) {
      disc = std::sqrt(disc);
      roots[0] = (-c1 - disc) / (2.0 * c2);
      if (in_range(roots[0])) ++n;
      roots[n] = (-c1 + disc) / (2.0 * c2);
      return in_range(roots[n]) ? n + 1 : n;
    }
    if (disc == 0.0) {
      roots[0] = -c1 / (2.0 * c2);
      return in_range(roots[0]) ? 1 : 0;
    }
    return 0;
  }
  if (c1 != 0.0) {
    roots[0] = -c0 / c1;
    return in_range(roots[0]) ? 1 : 0;
  }
  if (c0 == 0.0) {
    roots[0] = 0.0;
    return 1;
  }
  return 0;
}

double bezier_parameter_at_time(double x, const double q[4]) noexcept {
  const double c0 = q[0] - x;
  const double c1 = 3.0 * (q[1] - q[0]);
  const double c2 = 3.0 * (q[0] - 2.0 * q[1] + q[2]);
  const double c3 = q[3] - q[0] + 3.0 * (q[1] - q[2]);
  double roots[3];
  return solve_cubic_in_unit_interval(c0, c1, c2, c3, roots) > 0 ? roots[0] : -1.0;
}

double bezier_value(const double f[4], double u) noexcept {
  const double c0 = f[0];
  const double c1 = 3.0 * (f[1] - f[0]);
  const double c2 = 3.0 * (f[0] - 2.0 * f[1] + f[2]);
  const double c3 = f[3] - f[0] + 3.0 * (f[1] - f[2]);
  return c0 + u * (c1 + u * (c2 + u * c3));
}

}  // namespace avar::playback
