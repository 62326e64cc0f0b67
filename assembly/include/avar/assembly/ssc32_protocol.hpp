#pragma once
// Lynxmotion SSC-32 / SSC-32U boards: `ssc32: {}`.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/ssc32_link.hpp"

namespace avar::assembly {

firmware_iface::Ssc32LinkConfig ssc32_config(const rig::Rig& rig, std::size_t link);
const Protocol& ssc32_protocol();

}  // namespace avar::assembly
