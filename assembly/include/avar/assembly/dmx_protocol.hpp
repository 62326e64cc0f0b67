#pragma once
// ENTTEC DMX USB Pro widgets (one DMX512 universe): `dmx: {}`.

#include "avar/assembly/protocol.hpp"
#include <vector>

#include "avar/firmware_iface/dmx_link.hpp"

namespace avar::assembly {

/// The link's actuators as one DMX universe's (every DMX carrier: widget, Art-Net, sACN).
std::vector<firmware_iface::DmxActuator> dmx_actuators(const rig::Rig& rig, std::size_t link);
firmware_iface::DmxLinkConfig dmx_config(const rig::Rig& rig, std::size_t link);
const Protocol& dmx_protocol();

}  // namespace avar::assembly
