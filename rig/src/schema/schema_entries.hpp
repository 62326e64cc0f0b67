#pragma once
// The schemas of rig/src/schema/, listed by schemas() and drive_schemas().

#include "avar/rig/can_drive_schema.hpp"
#include "avar/rig/protocol_schema.hpp"

namespace avar::rig {

const ProtocolSchema& maestro_schema();
const ProtocolSchema& dynamixel_schema();
const ProtocolSchema& feetech_schema();
const ProtocolSchema& ssc32_schema();
const ProtocolSchema& dmx_schema();
const ProtocolSchema& can_schema();
const ProtocolSchema& gpio_schema();
const ProtocolSchema& artnet_schema();
const ProtocolSchema& sacn_schema();
const ProtocolSchema& pca9685_schema();
const ProtocolSchema& pwm_schema();
const ProtocolSchema& avar_device_schema();

/// The address rule every DMX carrier shares (a widget, Art-Net, sACN).
AddressRule dmx_slot_rule(const LinkSpec& link, bool fine);

const CanDriveSchema& odrive_schema();
const CanDriveSchema& cia402_schema();
const CanDriveSchema& mit_schema();

}  // namespace avar::rig
