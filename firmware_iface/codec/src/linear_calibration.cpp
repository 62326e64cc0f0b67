#include "avar/firmware_iface/linear_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace avar::firmware_iface {

double LinearCalibration::device_low() const noexcept { return std::min(device_at_min, device_at_max) + trim; }
double LinearCalibration::device_high() const noexcept { return std::max(device_at_min, device_at_max) + trim; }

double LinearCalibration::device_per_unit() const noexcept {
  return std::abs(device_at_max - device_at_min) / (channel_max - channel_min);
}

double LinearCalibration::to_device(double value, bool* clamped) const noexcept {
  const double lo = device_low();
  const double hi = device_high();
  if (!std::isfinite(value)) {
    if (clamped) *clamped = true;
    return 0.5 * (lo + hi);
  }
  const double s = (value - channel_min) / (channel_max - channel_min);
  const double from = reverse ? device_at_max : device_at_min;
  const double to = reverse ? device_at_min : device_at_max;
  const double raw = from + s * (to - from) + trim;
  const double out = std::clamp(raw, lo, hi);
  if (clamped) *clamped = out != raw;
  return out;
}

double LinearCalibration::to_channel(double device_value) const noexcept {
  const double from = reverse ? device_at_max : device_at_min;
  const double to = reverse ? device_at_min : device_at_max;
  const double s = (device_value - trim - from) / (to - from);
  return channel_min + s * (channel_max - channel_min);
}

}  // namespace avar::firmware_iface
