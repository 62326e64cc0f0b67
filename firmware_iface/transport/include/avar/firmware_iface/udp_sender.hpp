#pragma once
// Sends datagrams to one IPv4 destination over a non-blocking UDP socket: unicast, broadcast
// (only when asked) or multicast (with a TTL, loopback, and an optional outgoing interface).
// Fire and forget: nothing is read back. A datagram the kernel cannot queue right now is dropped
// and counted; the next tick sends a fresh one.

#include <atomic>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"

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

class UdpSender {
 public:
  /// Opens the socket. Throws std::invalid_argument for a host that is no numeric IPv4 address
  /// or port 0, std::runtime_error when the socket cannot be opened or set up.
  explicit UdpSender(const UdpDestination& destination);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  /// One datagram. ok when sent or dropped for a full queue (counted in dropped()); io_error
  /// when the network refuses it (unreachable, not permitted). Real-time safe: one non-blocking
  /// sendto, no allocation. One sending thread at a time.
  Status send(std::span<const std::uint8_t> datagram) noexcept;

  /// Counters, any thread.
  std::uint64_t datagrams_sent() const noexcept { return sent_.load(std::memory_order_relaxed); }
  std::uint64_t bytes_sent() const noexcept { return bytes_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  bool multicast() const noexcept { return multicast_; }
  /// "239.255.0.1:5568 (multicast)".
  const std::string& describe() const noexcept { return description_; }

 private:
  int fd_ = -1;
  std::uint32_t address_ = 0;  ///< network byte order
  std::uint16_t port_ = 0;     ///< network byte order
  bool multicast_ = false;
  std::string description_;
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> bytes_{0};
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace avar::firmware_iface
