#include "avar/sim/servo_model.hpp"

#include <algorithm>
#include <cmath>

namespace avar::sim {

void ServoModel::step(double dt_s, double pulse_us) noexcept {
  if (!(pulse_us > 0) || !(dt_s > 0)) return;
  const double error = pulse_us - position_;
  if (std::abs(error) <= params_.deadband_us) return;
  // Exact first-order response over dt for a constant pulse, then capped by the top speed.
  // 1 - exp(-x) lies in [0, 1], so the step never passes the pulse (time_constant 0 gives x = inf).
  const double lag_step = error * -std::expm1(-dt_s / params_.time_constant_s);
  const double cap = params_.max_speed_us_per_s * dt_s;
  position_ += std::clamp(lag_step, -cap, cap);
}

}  // namespace avar::sim
