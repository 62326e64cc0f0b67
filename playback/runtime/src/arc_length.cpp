#include "avar/playback/runtime/arc_length.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace avar::playback {
namespace {

// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 5> kNodes = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
constexpr std::array<double, 5> kWeights = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                                            0.2369268850561891};

double gauss5(const ParametricCurve& c, double a, double b) noexcept {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  double sum = 0;
  for (std::size_t i = 0; i < kNodes.size(); ++i) sum += kWeights[i] * c.derivative(mid + half * kNodes[i]).norm();
  return sum * half;
}

double adaptive(const ParametricCurve& c, double a, double b, double whole, double tolerance, int depth) noexcept {
  const double m = 0.5 * (a + b);
  const double left = gauss5(c, a, m), right = gauss5(c, m, b);
  // A non-finite length (an overflowing derivative) cannot converge: subdividing would only
  // visit all 2^kMaxArcLengthDepth intervals.
  if (depth >= kMaxArcLengthDepth || std::abs(left + right - whole) <= tolerance || !std::isfinite(left + right))
    return left + right;
  return adaptive(c, a, m, left, 0.5 * tolerance, depth + 1) + adaptive(c, m, b, right, 0.5 * tolerance, depth + 1);
}

}  // namespace

double arc_length(const ParametricCurve& curve, double a, double b, double tolerance) noexcept {
  if (a == b) return 0;
  if (b < a) return -arc_length(curve, b, a, tolerance);
  return adaptive(curve, a, b, gauss5(curve, a, b), tolerance, 0);
}

double parameter_at_length(const ParametricCurve& curve, double distance, double tolerance, double total_length) noexcept {
  const double u0 = curve.u_begin(), u1 = curve.u_end();
  // Half the bound for the quadrature, half for the root: |true length(u) - distance| <= tolerance.
  const double quad_tol = 0.5 * tolerance, root_tol = 0.5 * tolerance;
  const double total = total_length >= 0 ? total_length : arc_length(curve, u0, u1, quad_tol);
  if (!(distance > 0)) return u0;
  if (distance >= total) return u1;
  double lo = u0, hi = u1;
  double u = u0 + (u1 - u0) * distance / total;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = arc_length(curve, u0, u, quad_tol) - distance;
    if (std::abs(f) <= root_tol) return u;
    (f < 0 ? lo : hi) = u;
    const double speed = curve.derivative(u).norm();
    const double newton = speed > 0 ? u - f / speed : lo - 1;
    u = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
    if (hi - lo <= 1e-15 * std::max(1.0, std::abs(u))) return u;
  }
  return u;
}

ArcLengthTable::ArcLengthTable(const ParametricCurve& curve, double tolerance, std::size_t max_intervals)
    : u0_(curve.u_begin()), u1_(curve.u_end()) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) throw std::invalid_argument("arc-length table: tolerance must be above 0");
  if (!std::isfinite(u0_) || !std::isfinite(u1_) || !(u1_ > u0_))
    throw std::invalid_argument("arc-length table: the parameter range must be finite and not empty");
  for (std::size_t n = 8;; n *= 2) {
    h_ = (u1_ - u0_) / static_cast<double>(n);
    lengths_.assign(n + 1, 0.0);
    speeds_.assign(n + 1, 0.0);
    // Each interval's length gets its share of the tolerance, so the sum stays within it.
    const double share = 0.25 * tolerance / static_cast<double>(n);
    for (std::size_t i = 0; i <= n; ++i) {
      const double u = u0_ + static_cast<double>(i) * h_;
      speeds_[i] = curve.derivative(u).norm();
      if (i > 0) lengths_[i] = lengths_[i - 1] + arc_length(curve, u - h_, u, share);
    }
    bool fine = true;
    for (std::size_t i = 0; i < n && fine; ++i) {
      const double a = u0_ + static_cast<double>(i) * h_;
      const double mid = lengths_[i] + arc_length(curve, a, a + 0.5 * h_, share);
      fine = std::abs(hermite(i, 0.5) - mid) <= 0.5 * tolerance;
    }
    if (fine || 2 * n > max_intervals) return;
  }
}

double ArcLengthTable::hermite(std::size_t i, double w) const noexcept {
  const double w2 = w * w, w3 = w2 * w;
  return (2 * w3 - 3 * w2 + 1) * lengths_[i] + (w3 - 2 * w2 + w) * h_ * speeds_[i] + (-2 * w3 + 3 * w2) * lengths_[i + 1] +
         (w3 - w2) * h_ * speeds_[i + 1];
}

double ArcLengthTable::length_at(double u) const noexcept {
  if (!(u > u0_)) return 0;
  if (u >= u1_) return total_length();
  const double x = (u - u0_) / h_;
  const std::size_t i = std::min(static_cast<std::size_t>(x), intervals() - 1);
  return hermite(i, x - static_cast<double>(i));
}

double ArcLengthTable::parameter_at(double distance) const noexcept {
  if (!(distance > 0)) return u0_;
  if (distance >= total_length()) return u1_;
  const auto it = std::upper_bound(lengths_.begin(), lengths_.end(), distance);
  const std::size_t i = static_cast<std::size_t>(it - lengths_.begin()) - 1;
  const double span = lengths_[i + 1] - lengths_[i];
  double lo = 0, hi = 1;
  double w = span > 0 ? (distance - lengths_[i]) / span : 0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f = hermite(i, w) - distance;
    if (std::abs(f) <= 1e-15 * total_length()) break;
    (f < 0 ? lo : hi) = w;
    const double w2 = w * w;
    const double slope = (6 * w2 - 6 * w) * lengths_[i] + (3 * w2 - 4 * w + 1) * h_ * speeds_[i] +
                         (-6 * w2 + 6 * w) * lengths_[i + 1] + (3 * w2 - 2 * w) * h_ * speeds_[i + 1];
    const double newton = slope > 0 ? w - f / slope : -1;
    w = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
    if (hi - lo < 1e-14) break;
  }
  return u0_ + (static_cast<double>(i) + w) * h_;
}

}  // namespace avar::playback
