#pragma once
// Pololu Maestro links (settings: rig::MaestroOptions): on a serial port, or on native USB, where
// the link needs no port.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/maestro_link.hpp"
#include "avar/firmware_iface/maestro_usb_link.hpp"

namespace avar::assembly {

/// The Maestro driver settings for one link of the rig (calibrations and device-side limits).
firmware_iface::MaestroLinkConfig maestro_config(const rig::Rig& rig, std::size_t link);
/// The same for the native USB driver.
firmware_iface::MaestroUsbLinkConfig maestro_usb_config(const rig::Rig& rig, std::size_t link, const DriverTuning& tuning);
/// Finds the link's Maestro on USB and makes its driver. Throws InputError at the link's usb
/// setting naming what is missing ("no Maestro with serial 00012345 on USB (found: none)",
/// "libusb: no USB on this machine (...)") or a Maestro of another model than the link's.
std::unique_ptr<firmware_iface::ActuatorLink> open_maestro_usb(const rig::Rig& rig, std::size_t link);
/// Whether the link's port (as written or given with --port) opens the Maestro's virtual serial
/// port rather than finding it on USB: a link without usb, or any port given.
bool maestro_port_is_serial(const rig::LinkSpec& link, const std::string& port);
const Protocol& maestro_protocol();

}  // namespace avar::assembly
