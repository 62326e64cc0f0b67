#pragma once
// Feetech SCS / STS buses: `feetech: {series, readback, reply_timeout_ms, retries}`.

#include "avar/assembly/protocol.hpp"
#include "avar/assembly/servo_bus_options.hpp"
#include "avar/firmware_iface/feetech_link.hpp"

namespace avar::assembly {

/// The link's servo series (`series: sts` by default, or `scs`), validated.
firmware_iface::feetech::Series feetech_series(const rig::LinkSpec& link);
firmware_iface::FeetechLinkConfig feetech_config(const rig::Rig& rig, std::size_t link);
const Protocol& feetech_protocol();

}  // namespace avar::assembly
