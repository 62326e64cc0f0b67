#pragma once
// Calibration of a hobby-servo channel: channel units (degrees, mm, percent...) to pulse width
// in microseconds. Pure and real-time safe (no allocation, no exception).

namespace avar::firmware_iface {

struct PulseCalibration {
  double channel_min = 0;    ///< channel value mapped to us_at_min (channel units)
  double channel_max = 1;    ///< channel value mapped to us_at_max (channel units), > channel_min
  double us_at_min = 1000;   ///< pulse width at channel_min before reverse and trim (µs)
  double us_at_max = 2000;   ///< pulse width at channel_max before reverse and trim (µs)
  bool reverse = false;      ///< swap the two ends (servo mounted the other way round)
  double trim_us = 0;        ///< offset added to every pulse (re-centring after a horn re-seat)

  /// The hard pulse window: the calibrated span shifted by the trim. No pulse leaves it.
  double pulse_low_us() const noexcept;
  double pulse_high_us() const noexcept;

  /// Pulse width for a channel value, saturated to the hard window. Callers pass finite values;
  /// a non-finite one yields the window centre and counts as clamped. Sets *clamped when
  /// saturation changed the result.
  double to_pulse_us(double value, bool* clamped = nullptr) const noexcept;

  /// Inverse mapping: the channel value a pulse width stands for (not saturated).
  double to_channel(double pulse_us) const noexcept;

  /// Pulse change per channel unit (µs per unit, always positive).
  double us_per_unit() const noexcept;
};

}  // namespace avar::firmware_iface
