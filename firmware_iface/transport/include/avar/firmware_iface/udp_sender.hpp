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
#include "avar/firmware_iface/udp_destination.hpp"

namespace avar::firmware_iface {

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
