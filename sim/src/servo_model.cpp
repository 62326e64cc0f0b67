#include "avar/sim/servo_model.hpp"

#include <algorithm>
#include <cmath>

namespace avar::sim {

double lag_step(double error, double dt_s, double time_constant_s, double max_speed, double deadband) noexcept {
  if (std::abs(error) <= deadband) return 0;
  // 1 - exp(-x) lies in [0, 1], so the step never passes the goal (time_constant 0 gives x = inf).
  const double cap = max_speed * dt_s;
  return std::clamp(error * -std::expm1(-dt_s / time_constant_s), -cap, cap);
}

void ServoModel::step(double dt_s, double pulse_us) noexcept {
  if (!(pulse_us > 0) || !(dt_s > 0)) return;
  position_ += lag_step(pulse_us - position_, dt_s, params_.time_constant_s, params_.max_speed_us_per_s, params_.deadband_us);
}

}  // namespace avar::sim
