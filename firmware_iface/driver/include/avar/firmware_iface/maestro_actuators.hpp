#pragma once
// What every Maestro driver (serial: MaestroLink, native USB: MaestroUsbLink) does alike with its
// actuators: the checks of their device channels, their device-side limits in the Maestro's
// units, and each tick's target of one actuator.

#include <cstdint>
#include <optional>
#include <span>

#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct MaestroActuator {
  std::size_t channel = 0;  ///< rig channel index (position in the frames the loop sends)
  int device_channel = 0;   ///< Maestro channel, 0..channel_count-1
  LinearCalibration calibration;
  std::optional<double> speed_us_per_s;          ///< device-side speed limit
  std::optional<double> acceleration_us_per_s2;  ///< device-side acceleration limit
};

/// Throws std::invalid_argument for a device channel outside 0..channel_count-1 or used twice.
/// Load time.
void check_maestro_channels(std::span<const MaestroActuator> actuators, int channel_count);

/// The actuator's speed limit in device units of 25 µs/s; 0 (the Maestro's "unlimited") when it
/// has none. Real-time safe.
std::uint16_t maestro_speed_units(const MaestroActuator& a) noexcept;
/// The actuator's acceleration limit in device units of 312.5 µs/s²; 0 when it has none.
std::uint16_t maestro_acceleration_units(const MaestroActuator& a) noexcept;

/// Actuator i's target for `frame` (indexed by rig channel) in quarter-µs: its calibrated pulse
/// (saturated, and counted, by the table), or 0 (no pulses) once it is released. Real-time
/// safe; on the thread that calls the driver's send().
std::uint16_t maestro_target(ActuatorTable& table, std::size_t i, std::span<const double> frame) noexcept;

}  // namespace avar::firmware_iface
