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
  constexpr std::size_t kFirstIntervals = 8;
  const double narrowest = (u1_ - u0_) / static_cast<double>(std::max(max_intervals, kFirstIntervals));
  knots_.push_back(u0_);
  lengths_.push_back(0);
  speeds_.push_back(curve.derivative(u0_).norm());
  for (std::size_t i = 1; i <= kFirstIntervals; ++i) {
    const double b = i == kFirstIntervals ? u1_ : u0_ + (u1_ - u0_) * static_cast<double>(i) / kFirstIntervals;
    refine(curve, b, tolerance, narrowest);
  }
}

void ArcLengthTable::refine(const ParametricCurve& curve, double b, double tolerance, double narrowest) {
  const double a = knots_.back(), h = b - a;
  // Each interval's quadrature gets its width's share of a quarter of the tolerance, so the sum
  // over the table stays within it.
  const double share = 0.25 * tolerance * h / (u1_ - u0_);
  const double length = arc_length(curve, a, b, share);
  const double speed_b = curve.derivative(b).norm();
  const double start = lengths_.back();
  // The Hermite piece at w = 1/2: (L_a + L_b) / 2 + h (s_a - s_b) / 8.
  const double hermite_middle = 0.5 * (2 * start + length) + 0.125 * h * (speeds_.back() - speed_b);
  const double middle = start + arc_length(curve, a, a + 0.5 * h, share);
  const bool fine = std::abs(hermite_middle - middle) <= 0.5 * tolerance;
  // A non-finite length (an overflowing derivative) would not converge by halving either.
  if (fine || 0.5 * h < narrowest || !std::isfinite(length) || !std::isfinite(middle)) {
    knots_.push_back(b);
    lengths_.push_back(start + length);
    speeds_.push_back(speed_b);
    return;
  }
  refine(curve, a + 0.5 * h, tolerance, narrowest);
  refine(curve, b, tolerance, narrowest);
}

std::size_t ArcLengthTable::interval_of(double u) const noexcept {
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), u);
  const std::size_t after = static_cast<std::size_t>(it - knots_.begin());
  return std::clamp<std::size_t>(after, 1, intervals()) - 1;
}

double ArcLengthTable::hermite(std::size_t i, double w) const noexcept {
  const double h = knots_[i + 1] - knots_[i];
  const double w2 = w * w, w3 = w2 * w;
  return (2 * w3 - 3 * w2 + 1) * lengths_[i] + (w3 - 2 * w2 + w) * h * speeds_[i] + (-2 * w3 + 3 * w2) * lengths_[i + 1] +
         (w3 - w2) * h * speeds_[i + 1];
}

double ArcLengthTable::length_at(double u) const noexcept {
  if (!(u > u0_)) return 0;
  if (u >= u1_) return total_length();
  const std::size_t i = interval_of(u);
  return hermite(i, (u - knots_[i]) / (knots_[i + 1] - knots_[i]));
}

double ArcLengthTable::parameter_at(double distance) const noexcept {
  if (!(distance > 0)) return u0_;
  if (distance >= total_length()) return u1_;
  const auto it = std::upper_bound(lengths_.begin(), lengths_.end(), distance);
  const std::size_t i = static_cast<std::size_t>(it - lengths_.begin()) - 1;
  const double span = lengths_[i + 1] - lengths_[i];
  const double h = knots_[i + 1] - knots_[i];
  double lo = 0, hi = 1;
  double w = span > 0 ? (distance - lengths_[i]) / span : 0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f = hermite(i, w) - distance;
    if (std::abs(f) <= 1e-15 * total_length()) break;
    (f < 0 ? lo : hi) = w;
    const double w2 = w * w;
    const double slope = (6 * w2 - 6 * w) * lengths_[i] + (3 * w2 - 4 * w + 1) * h * speeds_[i] +
                         (-6 * w2 + 6 * w) * lengths_[i + 1] + (3 * w2 - 2 * w) * h * speeds_[i + 1];
    const double newton = slope > 0 ? w - f / slope : -1;
    w = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
    if (hi - lo < 1e-14) break;
  }
  return knots_[i] + w * h;
}

}  // namespace avar::playback
