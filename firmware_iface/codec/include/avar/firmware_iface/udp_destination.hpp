#pragma once
// A UDP destination as written ("HOST" or "HOST:PORT", numeric IPv4), parsed and checked. Pure:
// no socket, so that readers of settings (a rig's network links, a show's OSC cues) check a
// destination without linking a sender. Load-time only.

#include <cstdint>
#include <string>

namespace avar::firmware_iface {

struct UdpDestination {
  std::string host = "127.0.0.1";  ///< a numeric IPv4 address
  std::uint16_t port = 0;
  bool broadcast = false;           ///< allow a broadcast address (SO_BROADCAST)
  int multicast_ttl = 1;            ///< multicast only: hops, 1 = the local network
  bool multicast_loop = true;       ///< multicast only: deliver to listeners on this host too
  std::string multicast_interface;  ///< multicast only: the IPv4 address of the interface to send on; "" = the route's
};

/// "HOST" or "HOST:PORT" -> destination; the port stays `default_port` when absent. Throws
/// std::invalid_argument naming what is wrong (not a numeric IPv4 address, a port outside 1..65535).
UdpDestination parse_udp_destination(const std::string& text, std::uint16_t default_port);

/// Whether a numeric IPv4 address (host order) is multicast (224.0.0.0/4).
constexpr bool is_multicast_ipv4(std::uint32_t address) noexcept { return (address >> 28U) == 0xE; }

/// A numeric IPv4 address -> its value in network order. Throws std::invalid_argument naming
/// `what` when `host` is no numeric IPv4 address.
std::uint32_t parse_ipv4(const std::string& host, const char* what);

}  // namespace avar::firmware_iface
