#include "avar/firmware_iface/udp_sender.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace avar::firmware_iface {
namespace {

[[noreturn]] void udp_sender_fail(int fd, const std::string& what) {
  const std::string reason = std::strerror(errno);
  ::close(fd);
  throw std::runtime_error("UDP: cannot " + what + ": " + reason);
}

}  // namespace

UdpSender::UdpSender(const UdpDestination& destination) {
  address_ = parse_ipv4(destination.host, "the destination");
  if (destination.port == 0) throw std::invalid_argument("UDP destination " + destination.host + " needs a port");
  port_ = htons(destination.port);
  multicast_ = is_multicast_ipv4(ntohl(address_));
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) throw std::runtime_error("UDP: cannot open a socket: " + std::string(std::strerror(errno)));
  if (destination.broadcast) {
    const int on = 1;
    if (::setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &on, sizeof on) != 0) udp_sender_fail(fd_, "allow broadcast");
  }
  if (multicast_) {
    const int ttl = destination.multicast_ttl;
    const unsigned char loop = destination.multicast_loop ? 1 : 0;
    if (::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0) udp_sender_fail(fd_, "set the multicast TTL");
    if (::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) udp_sender_fail(fd_, "set multicast loopback");
    if (!destination.multicast_interface.empty()) {
      in_addr interface {};
      interface.s_addr = parse_ipv4(destination.multicast_interface, "the multicast interface");
      if (::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_IF, &interface, sizeof interface) != 0)
        udp_sender_fail(fd_, "choose the multicast interface " + destination.multicast_interface);
    }
  }
  description_ = destination.host + ":" + std::to_string(destination.port) +
                 (multicast_              ? " (multicast)"
                  : destination.broadcast ? " (broadcast)"
                                          : "");
}

UdpSender::~UdpSender() {
  if (fd_ >= 0) ::close(fd_);
}

Status UdpSender::send(std::span<const std::uint8_t> datagram) noexcept {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = address_;
  to.sin_port = port_;
  const ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT | MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&to), sizeof to);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return Status::ok;
    }
    return Status::io_error;
  }
  sent_.fetch_add(1, std::memory_order_relaxed);
  bytes_.fetch_add(static_cast<std::uint64_t>(n), std::memory_order_relaxed);
  return Status::ok;
}

}  // namespace avar::firmware_iface
