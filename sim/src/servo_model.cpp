#include "avar/sim/servo_model.hpp"

#include <algorithm>
#include <cmath>

namespace avar::sim {

void ServoModel::step(double dt_s, double pulse_us) noexcept {
  if (pulse_us <= 0 || dt_s <= 0) return;
  const double error = pulse_us - position_;
  if (std::abs(error) <= params_.deadband_us) return;
  // Exact first-order response over dt, then capped by the motor's top speed.
  const double lag_step = error * (1.0 - std::exp(-dt_s / params_.time_constant_s));
  const double cap = params_.max_speed_us_per_s * dt_s;
  position_ += std::clamp(lag_step, -cap, cap);
}

}  // namespace avar::sim
