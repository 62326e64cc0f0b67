#include "avar/control/limiter.hpp"

#include <algorithm>
#include <cmath>

namespace avar::control {

Limiter::Limiter(std::vector<ChannelLimits> limits)
    : limits_(std::move(limits)),
      last_(limits_.size(), 0.0),
      clamped_(limits_.size(), 0),
      rate_limited_(limits_.size(), 0) {
  for (std::size_t i = 0; i < limits_.size(); ++i) last_[i] = std::clamp(0.0, limits_[i].min, limits_[i].max);
}

void Limiter::reset(std::span<const double> pose) noexcept {
  for (std::size_t i = 0; i < limits_.size() && i < pose.size(); ++i)
    last_[i] = std::isfinite(pose[i]) ? std::clamp(pose[i], limits_[i].min, limits_[i].max) : last_[i];
}

Status Limiter::apply(std::span<const double> target, double dt_s, std::span<double> out) noexcept {
  Status status = Status::ok;
  for (std::size_t i = 0; i < limits_.size(); ++i) {
    const ChannelLimits& l = limits_[i];
    double v = target[i];
    if (!std::isfinite(v)) {
      status = Status::not_finite;
      out[i] = last_[i];
      continue;
    }
    if (v < l.min || v > l.max) {
      ++clamped_[i];
      v = std::clamp(v, l.min, l.max);
    }
    const double step = l.max_velocity * dt_s;
    const double moved = std::clamp(v, last_[i] - step, last_[i] + step);
    if (moved != v) ++rate_limited_[i];
    last_[i] = moved;
    out[i] = moved;
  }
  return status;
}

}  // namespace avar::control
