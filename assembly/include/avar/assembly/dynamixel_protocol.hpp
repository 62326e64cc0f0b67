#pragma once
// ROBOTIS DYNAMIXEL Protocol 2.0 buses: `dynamixel: {readback, reply_timeout_ms, retries}`.

#include "avar/assembly/protocol.hpp"
#include "avar/assembly/servo_bus_options.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"

namespace avar::assembly {

firmware_iface::DynamixelLinkConfig dynamixel_config(const rig::Rig& rig, std::size_t link);
const Protocol& dynamixel_protocol();

}  // namespace avar::assembly
