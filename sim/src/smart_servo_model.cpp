#include "avar/sim/smart_servo_model.hpp"

#include <algorithm>
#include <cmath>

#include "avar/sim/servo_model.hpp"

namespace avar::sim {

void SmartServoModel::advance(double dt_s, bool torque, double goal, double speed_limit, double acceleration_limit) noexcept {
  if (!(dt_s > 0)) return;
  const int steps = static_cast<int>(std::ceil(dt_s / kMaxStep_s));
  for (int i = 0; i < steps; ++i) step(dt_s / steps, torque, goal, speed_limit, acceleration_limit);
}

void SmartServoModel::step(double dt_s, bool torque, double goal, double speed_limit, double acceleration_limit) noexcept {
  if (torque) {
    const double top = speed_limit > 0 ? std::min(speed_limit, params_.max_speed) : params_.max_speed;
    const double most =
        acceleration_limit > 0 ? std::min(acceleration_limit, params_.max_acceleration) : params_.max_acceleration;
    const double wanted = lag_step(goal - position_, dt_s, params_.time_constant_s, top, params_.deadband) / dt_s;
    const double velocity = std::clamp(wanted, velocity_ - most * dt_s, velocity_ + most * dt_s);
    const double acceleration = (velocity - velocity_) / dt_s;
    velocity_ = velocity;
    position_ += velocity * dt_s;
    load_ = std::clamp(external_load_ + kLoadAtMaxAcceleration * acceleration / params_.max_acceleration +
                           kLoadAtMaxSpeed * velocity / params_.max_speed,
                       -1.0, 1.0);
  } else {
    velocity_ = 0;
    load_ = 0;
  }
  temperature_ +=
      (params_.heating_c_per_s_at_full_load * std::abs(load_) - params_.cooling_per_s * (temperature_ - params_.ambient_c)) *
      dt_s;
}

}  // namespace avar::sim
