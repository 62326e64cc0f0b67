#pragma once
// DMX512 on the network, one universe per link (settings: rig::ArtnetOptions, rig::SacnOptions):
// Art-Net 4 ArtDmx, unicast to the node (broadcast only with broadcast: true), and E1.31 sACN, to
// the universe's multicast group unless `to` names a receiver. Actuators take `address` (1..512) and `fine` (16-bit) as on a dmx
// link. The link needs no port; `port: sim` (or --sim) sends to a simulated node on loopback, and
// --port HOST[:PORT] sends to another receiver.

#include <string>

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/network_dmx_link.hpp"

namespace avar::assembly {

/// The driver's configuration of link `link` of a validated rig; `destination` "HOST[:PORT]"
/// replaces the rig's when not empty. Throws InputError at the link for a bad destination.
firmware_iface::ArtnetLinkConfig artnet_config(const rig::Rig& rig, std::size_t link, const std::string& destination);
firmware_iface::SacnLinkConfig sacn_config(const rig::Rig& rig, std::size_t link, const std::string& destination);

const Protocol& artnet_protocol();
const Protocol& sacn_protocol();

}  // namespace avar::assembly
