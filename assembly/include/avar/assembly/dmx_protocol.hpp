#pragma once
// ENTTEC DMX USB Pro widgets (one DMX512 universe): `dmx: {}`.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/dmx_link.hpp"

namespace avar::assembly {

firmware_iface::DmxLinkConfig dmx_config(const rig::Rig& rig, std::size_t link);
const Protocol& dmx_protocol();

}  // namespace avar::assembly
