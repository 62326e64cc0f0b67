#pragma once
// Calibration of one actuator: channel units (degrees, mm, percent...) to the device's own unit,
// linearly: pulse width in microseconds for hobby servos, position ticks for smart servos, DMX
// levels for dimmers. Pure and real-time safe (no allocation, no exception).

namespace avar::firmware_iface {

struct LinearCalibration {
  double channel_min = 0;       ///< channel value mapped to device_at_min (channel units)
  double channel_max = 1;       ///< channel value mapped to device_at_max (channel units), > channel_min
  double device_at_min = 1000;  ///< device value at channel_min before reverse and trim (device units)
  double device_at_max = 2000;  ///< device value at channel_max before reverse and trim (device units)
  bool reverse = false;         ///< swap the two ends (actuator mounted the other way round)
  double trim = 0;              ///< offset added to every device value (re-centring after a horn re-seat)

  /// The hard device window: the calibrated span shifted by the trim. No command leaves it.
  double device_low() const noexcept;
  double device_high() const noexcept;

  /// Device value for a channel value, saturated to the hard window. Callers pass finite values;
  /// a non-finite one yields the window centre and counts as clamped. Sets *clamped when
  /// saturation changed the result.
  double to_device(double value, bool* clamped = nullptr) const noexcept;

  /// Inverse mapping: the channel value a device value stands for (not saturated).
  double to_channel(double device_value) const noexcept;

  /// Device change per channel unit (always positive).
  double device_per_unit() const noexcept;
};

}  // namespace avar::firmware_iface
