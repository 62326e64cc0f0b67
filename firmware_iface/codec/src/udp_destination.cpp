#include "avar/firmware_iface/udp_destination.hpp"

#include <arpa/inet.h>

#include <cstdlib>
#include <stdexcept>

namespace avar::firmware_iface {

std::uint32_t parse_ipv4(const std::string& host, const char* what) {
  in_addr parsed{};
  if (::inet_pton(AF_INET, host.c_str(), &parsed) != 1)
    throw std::invalid_argument(std::string("expected ") + what + " to be a numeric IPv4 address such as 10.0.0.20, found '" +
                                host + "'");
  return parsed.s_addr;
}

UdpDestination parse_udp_destination(const std::string& text, std::uint16_t default_port) {
  UdpDestination d;
  d.port = default_port;
  const auto colon = text.find(':');
  d.host = text.substr(0, colon);
  if (colon != std::string::npos) {
    const std::string port = text.substr(colon + 1);
    char* end = nullptr;
    const long p = std::strtol(port.c_str(), &end, 10);
    if (port.empty() || *end != '\0' || p < 1 || p > 65535)
      throw std::invalid_argument("expected a UDP port from 1 to 65535 after the ':' of '" + text + "'");
    d.port = static_cast<std::uint16_t>(p);
  }
  parse_ipv4(d.host, "the destination");
  return d;
}

}  // namespace avar::firmware_iface
