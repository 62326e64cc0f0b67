#include "avar/playback/runtime/distance_time.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "avar/core/portable_math.hpp"

namespace avar::playback {
namespace {

constexpr const char* kShapeNames[] = {"linear", "sine", "sine_constant_middle", "parabolic", "cubic", "user"};

}  // namespace

std::optional<DistanceTimeShape> distance_time_shape_from_name(std::string_view name) {
  for (std::size_t i = 0; i + 1 < std::size(kShapeNames); ++i)
    if (name == kShapeNames[i]) return static_cast<DistanceTimeShape>(i);
  return std::nullopt;
}

const char* to_string(DistanceTimeShape shape) { return kShapeNames[static_cast<std::size_t>(shape)]; }

DistanceTime::DistanceTime(DistanceTimeShape shape, double k1, double k2) : shape_(shape), k1_(k1), k2_(k2) {
  if (!(k1 >= 0 && k1 <= k2 && k2 <= 1)) throw std::invalid_argument("distance-time function: expected 0 <= k1 <= k2 <= 1");
  const double two_over_pi = 2 / std::numbers::pi;
  if (shape == DistanceTimeShape::sine_constant_middle) scale_ = 1 / (k1 * two_over_pi + (k2 - k1) + (1 - k2) * two_over_pi);
  if (shape == DistanceTimeShape::parabolic) scale_ = 2 / (1 + k2 - k1);
}

double DistanceTime::distance(double t) const noexcept {
  if (!(t > 0)) return 0;
  if (t >= 1) return 1;
  const double pi = std::numbers::pi, two_over_pi = 2 / pi;
  switch (shape_) {
    case DistanceTimeShape::linear: return t;
    case DistanceTimeShape::sine: return 0.5 * (1 - pmath::cos(pi * t));
    case DistanceTimeShape::cubic: return t * t * (3 - 2 * t);
    case DistanceTimeShape::user: return std::clamp(user_.evaluate(t), 0.0, 1.0);
    case DistanceTimeShape::sine_constant_middle: {
      // Unnormalised distance: the ease-in quarter sine covers k1 (2/pi) at unit top speed.
      double d;
      if (t < k1_) d = k1_ * two_over_pi * (1 - pmath::cos(0.5 * pi * t / k1_));
      else if (t <= k2_) d = k1_ * two_over_pi + (t - k1_);
      else d = k1_ * two_over_pi + (k2_ - k1_) + (1 - k2_) * two_over_pi * pmath::sin(0.5 * pi * (t - k2_) / (1 - k2_));
      return std::min(1.0, d * scale_);
    }
    case DistanceTimeShape::parabolic: {
      const double v = scale_;
      double d;
      if (t < k1_) d = 0.5 * v * t * t / k1_;
      else if (t <= k2_) d = v * (0.5 * k1_ + (t - k1_));
      else {
        const double r = t - k2_;
        d = v * (0.5 * k1_ + (k2_ - k1_)) + v * r - 0.5 * v * r * r / (1 - k2_);
      }
      return std::min(1.0, d);
    }
  }
  return t;
}

double DistanceTime::speed(double t) const noexcept {
  if (!(t >= 0 && t <= 1)) return 0;
  const double pi = std::numbers::pi;
  switch (shape_) {
    case DistanceTimeShape::linear: return 1;
    case DistanceTimeShape::sine: return 0.5 * pi * pmath::sin(pi * t);
    case DistanceTimeShape::cubic: return 6 * t * (1 - t);
    case DistanceTimeShape::user: {
      constexpr double h = 1e-6;
      const double a = std::max(0.0, t - h), b = std::min(1.0, t + h);
      return (distance(b) - distance(a)) / (b - a);
    }
    case DistanceTimeShape::sine_constant_middle:
      if (t < k1_) return scale_ * pmath::sin(0.5 * pi * t / k1_);
      if (t <= k2_) return scale_;
      return scale_ * pmath::cos(0.5 * pi * (t - k2_) / (1 - k2_));
    case DistanceTimeShape::parabolic:
      if (t < k1_) return scale_ * t / k1_;
      if (t <= k2_) return scale_;
      return scale_ * (1 - (t - k2_) / (1 - k2_));
  }
  return 1;
}

}  // namespace avar::playback
