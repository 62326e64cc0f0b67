#pragma once
// Pololu Maestro links: `maestro: {model, device_number, crc, baud_detect}`.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/maestro_link.hpp"

namespace avar::assembly {

/// Settings of a Pololu Maestro link.
struct MaestroOptions {
  int channel_count = 24;    ///< 6 (Micro), 12, 18 or 24 (Mini)
  bool pololu_form = false;  ///< address by device number (daisy chains) instead of compact
  std::uint8_t device_number = 12;
  bool crc = false;          ///< append CRC-7 (the device's "Enable CRC" setting)
  bool baud_detect = false;  ///< send 0xAA first (device in "UART, detect baud rate" mode)
};

/// The link's settings, validated (InputError at the offending setting).
MaestroOptions maestro_options(const rig::LinkSpec& link);
/// The Maestro driver settings for one link of the rig (calibrations and device-side limits).
firmware_iface::MaestroLinkConfig maestro_config(const rig::Rig& rig, std::size_t link);
const Protocol& maestro_protocol();

}  // namespace avar::assembly
