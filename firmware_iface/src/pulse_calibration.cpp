#include "avar/firmware_iface/pulse_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace avar::firmware_iface {

double PulseCalibration::pulse_low_us() const noexcept { return std::min(us_at_min, us_at_max) + trim_us; }
double PulseCalibration::pulse_high_us() const noexcept { return std::max(us_at_min, us_at_max) + trim_us; }

double PulseCalibration::us_per_unit() const noexcept {
  return std::abs(us_at_max - us_at_min) / (channel_max - channel_min);
}

double PulseCalibration::to_pulse_us(double value, bool* clamped) const noexcept {
  const double lo = pulse_low_us();
  const double hi = pulse_high_us();
  if (!std::isfinite(value)) {
    if (clamped) *clamped = true;
    return 0.5 * (lo + hi);
  }
  const double s = (value - channel_min) / (channel_max - channel_min);
  const double from = reverse ? us_at_max : us_at_min;
  const double to = reverse ? us_at_min : us_at_max;
  const double us = from + s * (to - from) + trim_us;
  const double out = std::clamp(us, lo, hi);
  if (clamped) *clamped = out != us;
  return out;
}

double PulseCalibration::to_channel(double pulse_us) const noexcept {
  const double from = reverse ? us_at_max : us_at_min;
  const double to = reverse ? us_at_min : us_at_max;
  const double s = (pulse_us - trim_us - from) / (to - from);
  return channel_min + s * (channel_max - channel_min);
}

}  // namespace avar::firmware_iface
