#include "avar/playback/runtime/bezier_time_solve.hpp"

#include <cmath>

#include "avar/core/portable_math.hpp"

namespace avar::playback {
namespace {

// Blender tests each root after rounding it to float: SMALL (-1e-10) <= root <= 1.000001f.
bool accepted(double u) noexcept {
  const auto f = static_cast<float>(u);
  return f >= static_cast<float>(-1.0e-10) && f <= 1.000001f;
}

// Appends u to roots when accepted; returns the new count.
int keep(double u, double roots[3], int n) noexcept {
  roots[n] = u;
  return accepted(u) ? n + 1 : n;
}

constexpr double kNegligibleCubic = 1.0e-9;

}  // namespace

Cubic bezier_polynomial(const double p[4]) noexcept {
  return {p[0], 3.0 * (p[1] - p[0]), 3.0 * (p[0] - 2.0 * p[1] + p[2]), p[3] - p[0] + 3.0 * (p[1] - p[2])};
}

void correct_bezier_handles(double time[4], double value[4]) noexcept {
  const double length = time[3] - time[0];
  // Offsets of each key from its handle (Blender's h1 and h2).
  const double h1t = time[0] - time[1], h1v = value[0] - value[1];
  const double h2t = time[3] - time[2], h2v = value[3] - value[2];
  const double extent1 = std::abs(h1t), extent2 = std::abs(h2t);
  if (extent1 + extent2 == 0.0) return;
  if (extent1 > length) {
    const double fac = length / extent1;
    time[1] = time[0] - fac * h1t;
    value[1] = value[0] - fac * h1v;
  }
  if (extent2 > length) {
    const double fac = length / extent2;
    time[2] = time[3] - fac * h2t;
    value[2] = value[3] - fac * h2v;
  }
}

int solve_cubic_in_unit_interval(double c0, double c1, double c2, double c3, double roots[3]) noexcept {
  // Blender divides by c3 whenever it is not exactly zero. Rounding rarely leaves an exact zero
  // where the handles make the time cubic degenerate (handles at thirds give x(u) linear), and
  // dividing by a rounding residue makes the shift a = c2 / 3 c3 huge and the root all
  // cancellation, so such a residue counts as zero here: the roots in [0, 1] move by about
  // |c3| / |x'|, far below Blender's own float rounding.
  if (c3 != 0.0 && std::abs(c3) > kNegligibleCubic * (std::abs(c1) + std::abs(c2))) {
    // Monic cubic u^3 + 3a u^2 + b u + c; with u = y - a it becomes y^3 + 3p y + 2q = 0.
    const double a = c2 / c3 / 3.0;
    const double b = c1 / c3;
    const double c = c0 / c3;
    const double p = b / 3.0 - a * a;
    const double q = (2.0 * a * a * a - a * b + c) / 2.0;
    const double d = q * q + p * p * p;
    if (d > 0.0) {
      // One real root, Cardano: y = cbrt(-q + sqrt d) + cbrt(-q - sqrt d). The two cube roots
      // multiply to -p, so the one of larger magnitude is taken and the other is -p divided by
      // it: the same root without the cancellation of adding two nearly opposite terms.
      const double big = pmath::cbrt(-q - std::copysign(std::sqrt(d), q));
      return keep(big - p / big - a, roots, 0);
    }
    if (d == 0.0) {
      // A double root: the simple root 2t - a first, then the double one -t - a.
      const double t = pmath::cbrt(-q);
      const int n = keep(2.0 * t - a, roots, 0);
      return keep(-t - a, roots, n);
    }
    // Three real roots, trigonometric form y = 2 sqrt(-p) cos((phi + 2 pi k) / 3). Blender's order:
    // the largest (k = 0), the smallest, the middle one.
    const double phi = pmath::acos(-q / std::sqrt(-(p * p * p)));
    const double t = std::sqrt(-p);
    const double cp = pmath::cos(phi / 3.0);
    const double sq = std::sqrt(3.0 - 3.0 * cp * cp);
    int n = keep(2.0 * t * cp - a, roots, 0);
    n = keep(-t * (cp + sq) - a, roots, n);
    return keep(-t * (cp - sq) - a, roots, n);
  }
  if (c2 != 0.0) {
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc > 0.0) {
      // (-c1 - sqrt D) / 2 c2 first, then (-c1 + sqrt D) / 2 c2, each computed in the form that
      // does not subtract nearly equal numbers (the product of the roots is c0 / c2).
      const double s = std::sqrt(disc);
      const double minus = c1 >= 0.0 ? (-c1 - s) / (2.0 * c2) : 2.0 * c0 / (-c1 + s);
      const double plus = c1 >= 0.0 ? 2.0 * c0 / (-c1 - s) : (-c1 + s) / (2.0 * c2);
      return keep(plus, roots, keep(minus, roots, 0));
    }
    if (disc == 0.0) return keep(-c1 / (2.0 * c2), roots, 0);
    return 0;
  }
  if (c1 != 0.0) return keep(-c0 / c1, roots, 0);
  if (c0 == 0.0) {
    roots[0] = 0.0;
    return 1;
  }
  return 0;
}

double bezier_parameter_at_time(double x, const double q[4]) noexcept {
  Cubic time = bezier_polynomial(q);
  time.c0 -= x;
  double roots[3];
  return solve_cubic_in_unit_interval(time.c0, time.c1, time.c2, time.c3, roots) > 0 ? roots[0] : -1.0;
}

double bezier_value(const double f[4], double u) noexcept { return bezier_polynomial(f).at(u); }

}  // namespace avar::playback
