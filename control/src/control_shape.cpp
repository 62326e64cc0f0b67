#include "avar/control/control_shape.hpp"

#include <algorithm>
#include <cmath>

namespace avar::control {

ShapedValue shape_control(double raw, bool bipolar, const ControlShape& shape) noexcept {
  double x = std::isfinite(raw) ? raw : 0.0;
  if (shape.input) {
    x = (x - shape.input->first) / (shape.input->second - shape.input->first);
    bipolar = false;
  }
  x = bipolar ? std::clamp(x, -1.0, 1.0) : std::clamp(x, 0.0, 1.0);
  if (shape.invert) x = bipolar ? -x : 1.0 - x;
  // Dead zone and expo act on the magnitude; the sign (bipolar) is kept.
  const double sign = x < 0 ? -1.0 : 1.0;
  double m = std::abs(x);
  if (shape.dead_zone > 0) m = m <= shape.dead_zone ? 0.0 : (m - shape.dead_zone) / (1.0 - shape.dead_zone);
  m = (1.0 - shape.expo) * m + shape.expo * m * m * m;
  return {sign * m, bipolar};
}

}  // namespace avar::control
