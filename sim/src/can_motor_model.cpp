#include "avar/sim/can_motor_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avar::sim {

void CanMotorModel::advance(double dt_s, const MotorCommand& c) noexcept {
  while (dt_s > 0) {
    const double h = std::min(dt_s, kMaxStep_s);
    dt_s -= h;
    double torque = 0;
    if (c.enabled)
      torque = std::clamp(c.kp * (c.position - position_) + c.kd * (c.velocity - velocity_) + c.torque_ff, -params_.max_torque,
                          params_.max_torque);
    torque_ = torque;
    const double net = torque - external_torque_ * (c.enabled ? 1.0 : 0.0) - params_.viscous_friction * velocity_;
    double v = velocity_ + h * net / params_.inertia;
    if (!c.enabled) {
      // Without torque the rotor coasts down; it never speeds up on its own.
      if (v * velocity_ <= 0) v = 0;
    }
    velocity_ = std::clamp(v, -params_.max_velocity, params_.max_velocity);
    position_ += h * velocity_;
  }
}

double CanMotorModel::measured_position() const noexcept {
  const double step = 2 * std::numbers::pi / params_.encoder_counts_per_turn;
  return std::round(position_ / step) * step;
}

double CanMotorModel::critical_kd(double kp) const noexcept { return 2 * std::sqrt(kp * params_.inertia); }

}  // namespace avar::sim
