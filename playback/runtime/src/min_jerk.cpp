#include "avar/playback/runtime/min_jerk.hpp"

#include <algorithm>
#include <cmath>

#include "avar/core/portable_math.hpp"

namespace avar::playback {

double min_jerk(double x) noexcept {
  const double t = std::clamp(x, 0.0, 1.0);
  return t * t * t * (t * (t * 6 - 15) + 10);
}

double min_jerk_duration(double amplitude, const IdleChannelLimits& limits, double share, double at_least) noexcept {
  const double a = std::abs(amplitude);
  double t = at_least;
  if (limits.max_velocity > 0) t = std::max(t, kMinJerkPeakVelocity * a / (share * limits.max_velocity));
  if (limits.max_acceleration > 0) t = std::max(t, std::sqrt(kMinJerkPeakAcceleration * a / (share * limits.max_acceleration)));
  if (limits.max_jerk > 0) t = std::max(t, pmath::cbrt(kMinJerkPeakJerk * a / (share * limits.max_jerk)));
  return t;
}

}  // namespace avar::playback
