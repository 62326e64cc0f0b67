#include "avar/control/ramp.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace avar::control {

Ramp::Ramp(std::size_t channels, std::vector<char> at_once)
    : from_(channels, 0.0), to_(channels, 0.0), at_once_(std::move(at_once)) {
  at_once_.resize(channels, 0);
}

void Ramp::plan(std::span<const double> from, std::span<const double> to, std::span<const double> peak_velocity,
                double min_duration_s) noexcept {
  double duration = min_duration_s;
  for (std::size_t i = 0; i < from_.size(); ++i) {
    from_[i] = from[i];
    to_[i] = to[i];
    const double distance = std::abs(to[i] - from[i]);
    if (peak_velocity[i] > 0 && !at_once_[i])
      duration = std::max(duration, std::numbers::pi * distance / (2.0 * peak_velocity[i]));
  }
  duration_ = duration;
}

void Ramp::sample(double t_s, std::span<double> out) const noexcept {
  const double s = duration_ > 0 ? std::clamp(t_s / duration_, 0.0, 1.0) : 1.0;
  const double w = 0.5 * (1.0 - std::cos(std::numbers::pi * s));
  for (std::size_t i = 0; i < from_.size(); ++i) out[i] = s >= 1.0 || at_once_[i] ? to_[i] : from_[i] + w * (to_[i] - from_[i]);
}

}  // namespace avar::control
