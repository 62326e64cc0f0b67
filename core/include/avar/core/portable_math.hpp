#pragma once
// The elementary functions of the curve engine, the same bits wherever it is compiled: natively
// (glibc) and to WebAssembly (emscripten's musl), whose libm differ in the last bits of sin, cos,
// asin, acos, cbrt, pow and hypot. Each function here uses only + - * / and sqrt (correctly
// rounded by IEEE 754), and exact operations (floor, ldexp, frexp, copysign), in a fixed order,
// so that two builds that do not contract a*b+c into a fused multiply-add (-ffp-contract=off)
// give identical results.
//
// Accuracy: within a few units in the last place of the true value over the domains the
// curves use (tests/core/portable_math_test.cpp measures it against glibc). Large arguments of
// sin and cos (|x| > 2^19 pi) lose accuracy but stay deterministic.
//
// Pure, header-only, constexpr-free (the order of evaluation is the contract): real-time safe.

#include <cmath>
#include <limits>

namespace avar::pmath {

inline constexpr double kPi = 3.141592653589793;
inline constexpr double kHalfPi = 1.5707963267948966;

namespace detail {

// pi/2 in three parts: the first two have 33 significant bits, so n * part is exact for
// |n| < 2^20 (Cody and Waite's reduction).
inline constexpr double kHalfPi1 = 1.57079632673412561417e+00;
inline constexpr double kHalfPi2 = 6.07710050630396597660e-11;
inline constexpr double kHalfPi3 = 2.02226624879595063154e-21;
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;

/// c[0] + z (c[1] + z (c[2] + ...)), from the last coefficient.
template <int N>
double horner(const double (&c)[N], double z) {
  double p = c[N - 1];
  for (int i = N - 2; i >= 0; --i) p = p * z + c[i];
  return p;
}

/// sin r for |r| <= pi/4: the Taylor series to r^21, in r^2.
inline double sin_kernel(double r) {
  static constexpr double kTerms[] = {1.0 / 6.0,
                                      -1.0 / 120.0,
                                      1.0 / 5040.0,
                                      -1.0 / 362880.0,
                                      1.0 / 39916800.0,
                                      -1.0 / 6227020800.0,
                                      1.0 / 1307674368000.0,
                                      -1.0 / 355687428096000.0,
                                      1.0 / 121645100408832000.0,
                                      -1.0 / 51090942171709440000.0};  // 1/3!, -1/5!, ... -1/21!
  const double z = r * r;
  return r - r * (z * horner(kTerms, z));
}

/// cos r for |r| <= pi/4: the Taylor series to r^22, in r^2.
inline double cos_kernel(double r) {
  static constexpr double kTerms[] = {1.0 / 24.0,
                                      -1.0 / 720.0,
                                      1.0 / 40320.0,
                                      -1.0 / 3628800.0,
                                      1.0 / 479001600.0,
                                      -1.0 / 87178291200.0,
                                      1.0 / 20922789888000.0,
                                      -1.0 / 6402373705728000.0,
                                      1.0 / 2432902008176640000.0,
                                      -1.0 / 1124000727777607680000.0};  // 1/4!, -1/6!, ... -1/22!
  const double z = r * r;
  // 1 - z/2 + z^2 p, with 1 - z/2 formed last for the small terms' bits.
  const double half = 0.5 * z;
  return (1.0 - half) + ((1.0 - (1.0 - half)) - half + z * (z * horner(kTerms, z)));
}

/// x reduced to [-pi/4, pi/4] and the quadrant it fell in (x = r + quadrant * pi/2).
inline double reduce(double x, long long& quadrant) {
  const double n = std::floor(x * kTwoOverPi + 0.5);
  quadrant = static_cast<long long>(n);
  return ((x - n * kHalfPi1) - n * kHalfPi2) - n * kHalfPi3;
}

/// asin x for |x| <= 0.5: its series sum_k (2k)! / (4^k (k!)^2 (2k+1)) x^(2k+1) to k = 30,
/// summed from the smallest term.
inline double asin_series(double x) {
  const double z = x * x;
  double c[31];
  c[0] = 1.0;
  for (int k = 1; k <= 30; ++k) c[k] = c[k - 1] * (2.0 * k - 1.0) / (2.0 * k);
  double p = c[30] / 61.0;
  for (int k = 29; k >= 1; --k) p = p * z + c[k] / (2.0 * k + 1.0);
  return x + x * (z * p);
}

}  // namespace detail

inline double sin(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  long long q = 0;
  const double r = detail::reduce(x, q);
  switch (q & 3) {
    case 0: return detail::sin_kernel(r);
    case 1: return detail::cos_kernel(r);
    case 2: return -detail::sin_kernel(r);
    default: return -detail::cos_kernel(r);
  }
}

inline double cos(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  long long q = 0;
  const double r = detail::reduce(x, q);
  switch (q & 3) {
    case 0: return detail::cos_kernel(r);
    case 1: return -detail::sin_kernel(r);
    case 2: return -detail::cos_kernel(r);
    default: return detail::sin_kernel(r);
  }
}

/// asin on [-1, 1]; NaN outside.
inline double asin(double x) {
  if (!(x >= -1.0 && x <= 1.0)) return std::numeric_limits<double>::quiet_NaN();
  const double a = std::fabs(x);
  if (a <= 0.5) return detail::asin_series(x);
  // asin a = pi/2 - 2 asin(sqrt((1 - a) / 2)), whose argument is at most 0.5.
  const double s = std::sqrt((1.0 - a) * 0.5);
  return std::copysign(kHalfPi - 2.0 * detail::asin_series(s), x);
}

/// acos on [-1, 1]; NaN outside.
inline double acos(double x) {
  if (!(x >= -1.0 && x <= 1.0)) return std::numeric_limits<double>::quiet_NaN();
  if (x > 0.5) return 2.0 * detail::asin_series(std::sqrt((1.0 - x) * 0.5));
  if (x < -0.5) return kPi - 2.0 * detail::asin_series(std::sqrt((1.0 + x) * 0.5));
  return kHalfPi - detail::asin_series(x);
}

/// The real cube root.
inline double cbrt(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  const double a = std::fabs(x);
  // a = m 2^e with m in [0.5, 1): a first guess from the exponent, then Newton's steps on
  // y^3 = a, which double the correct bits each (quadratic), from at least 3.
  int e = 0;
  const double m = std::frexp(a, &e);
  int e3 = e / 3;
  int rem = e - 3 * e3;
  if (rem < 0) {
    rem += 3;
    e3 -= 1;
  }
  // m 2^rem in [0.5, 4): cube root in [0.79, 1.59]; a quadratic fit is within 3 %.
  const double w = std::ldexp(m, rem);
  double y = 0.5688 + w * (0.5244 - w * 0.0522);
  for (int i = 0; i < 5; ++i) y = y + (w / (y * y) - y) / 3.0;
  return std::copysign(std::ldexp(y, e3), x);
}

/// 2^x.
inline double exp2(double x) {
  if (std::isnan(x)) return x;
  if (x >= 1024.0) return std::numeric_limits<double>::infinity();
  if (x < -1075.0) return 0.0;
  const double n = std::floor(x + 0.5);
  const double f = x - n;                   // exact, |f| <= 0.5
  const double g = f * 0.6931471805599453;  // ln 2
  // e^g for |g| <= 0.347: Taylor to g^16.
  static constexpr double kTerms[] = {1.0 / 2.0,
                                      1.0 / 6.0,
                                      1.0 / 24.0,
                                      1.0 / 120.0,
                                      1.0 / 720.0,
                                      1.0 / 5040.0,
                                      1.0 / 40320.0,
                                      1.0 / 362880.0,
                                      1.0 / 3628800.0,
                                      1.0 / 39916800.0,
                                      1.0 / 479001600.0,
                                      1.0 / 6227020800.0,
                                      1.0 / 87178291200.0,
                                      1.0 / 1307674368000.0,
                                      1.0 / 20922789888000.0};  // 1/2! ... 1/16!
  const double p = detail::horner(kTerms, g);
  const double e = 1.0 + (g + g * (g * p));
  // Scaled in two steps so that a result near the subnormal range is rounded once.
  const int k = static_cast<int>(n);
  return k < -1000 ? std::ldexp(std::ldexp(e, k + 1000), -1000) : std::ldexp(e, k);
}

/// sqrt(x^2 + y^2) without overflow or underflow in the squares.
inline double hypot(double x, double y) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  if (std::isinf(ax) || std::isinf(ay)) return std::numeric_limits<double>::infinity();
  if (std::isnan(ax) || std::isnan(ay)) return std::numeric_limits<double>::quiet_NaN();
  const double big = ax > ay ? ax : ay;
  const double small = ax > ay ? ay : ax;
  if (big == 0.0) return 0.0;
  const double r = small / big;
  return big * std::sqrt(1.0 + r * r);
}

}  // namespace avar::pmath
