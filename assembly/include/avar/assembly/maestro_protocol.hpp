#pragma once
// Pololu Maestro links: `maestro: {model, device_number, crc, baud_detect}` on a serial port, or
// `maestro: {model, usb: SERIAL}` (usb: any for the only Maestro present) on native USB, where the
// link needs no port.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/maestro_link.hpp"
#include "avar/firmware_iface/maestro_usb_link.hpp"

namespace avar::assembly {

/// Settings of a Pololu Maestro link.
struct MaestroOptions {
  int channel_count = 24;    ///< 6 (Micro), 12, 18 or 24 (Mini)
  bool pololu_form = false;  ///< address by device number (daisy chains) instead of compact
  std::uint8_t device_number = 12;
  bool crc = false;          ///< append CRC-7 (the device's "Enable CRC" setting)
  bool baud_detect = false;  ///< send 0xAA first (device in "UART, detect baud rate" mode)
  bool usb = false;          ///< native USB (vendor requests) instead of a serial port
  std::string usb_serial;    ///< with usb: the serial number string; empty: the only Maestro present
};

/// The link's settings, validated (InputError at the offending setting).
MaestroOptions maestro_options(const rig::LinkSpec& link);
/// The Maestro driver settings for one link of the rig (calibrations and device-side limits).
firmware_iface::MaestroLinkConfig maestro_config(const rig::Rig& rig, std::size_t link);
/// The same for the native USB driver.
firmware_iface::MaestroUsbLinkConfig maestro_usb_config(const rig::Rig& rig, std::size_t link, const DriverTuning& tuning);
/// Finds the link's Maestro on USB and makes its driver. Throws InputError at the link's usb
/// setting naming what is missing ("no Maestro with serial 00012345 on USB (found: none)",
/// "libusb: no USB on this machine (...)") or a Maestro of another model than the link's.
std::unique_ptr<firmware_iface::ActuatorLink> open_maestro_usb(const rig::Rig& rig, std::size_t link);
const Protocol& maestro_protocol();

}  // namespace avar::assembly
