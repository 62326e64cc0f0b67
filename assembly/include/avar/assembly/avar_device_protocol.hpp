#pragma once
// A device running avar's streaming player on a serial port: `avar-device: {knot_ms, lead_ms,
// device_rate, device_knots, device_watchdog_ms}`. Each actuator is one of the device's outputs
// (`output: 0..n-1`, one per channel) with the pulse range the device drives it over (`min_us`,
// `max_us`). The link streams knots, not positions (docs/protocols/avar-device.md).

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/avar_device_link.hpp"

namespace avar::assembly {

/// The link's settings from avar-device link `link` of a validated rig. Throws InputError at an
/// actuator whose output is not one of 0..n-1 (n the link's actuators) or is given twice.
firmware_iface::AvarDeviceLinkConfig avar_device_config(const rig::Rig& rig, std::size_t link, const DriverTuning& tuning);
const Protocol& avar_device_protocol();

}  // namespace avar::assembly
