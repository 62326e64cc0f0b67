#pragma once
// DMX512 on the network, one universe per link: `artnet: {to: 10.0.0.20, net: 0, subnet: 0,
// universe: 1}` (Art-Net 4 ArtDmx, unicast to the node; broadcast only with broadcast: true) and
// `sacn: {universe: 1, priority: 100}` (E1.31, to the universe's multicast group unless `to`
// names a receiver). Actuators take `address` (1..512) and `fine` (16-bit) as on a dmx link.
// The link needs no port; `port: sim` (or --sim) sends to a simulated node on loopback, and
// --port HOST[:PORT] sends to another receiver.

#include <string>

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/network_dmx_link.hpp"

namespace avar::assembly {

/// The driver's configuration of link `link` of a validated rig; `destination` "HOST[:PORT]"
/// replaces the rig's when not empty. Throws InputError at the link for a bad destination.
firmware_iface::ArtnetLinkConfig artnet_config(const rig::Rig& rig, std::size_t link, const std::string& destination);
firmware_iface::SacnLinkConfig sacn_config(const rig::Rig& rig, std::size_t link, const std::string& destination);

/// "01234567-89ab-cdef-0123-456789abcdef" -> CID; false when the text is no UUID.
bool parse_cid(const std::string& text, firmware_iface::sacn::Cid& cid);

const Protocol& artnet_protocol();
const Protocol& sacn_protocol();

}  // namespace avar::assembly
