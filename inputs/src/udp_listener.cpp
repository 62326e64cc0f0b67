#include "avar/inputs/udp_listener.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"

namespace avar::inputs {
namespace {

constexpr std::size_t kUdpMaxDatagram = 65536;

std::string udp_bind_error(const std::string& what, const std::string& where, int error) {
  std::string why;
  switch (error) {
    case EADDRINUSE: why = "address in use: another program, or another avar, listens there"; break;
    case EADDRNOTAVAIL: why = "no interface of this machine has that address"; break;
    case EACCES: why = "ports below 1024 need privileges"; break;
    default: why = std::strerror(error);
  }
  return what + ": cannot listen on " + where + " (" + why + ")";
}

}  // namespace

UdpListener::UdpListener(std::string host, std::uint16_t port, std::string what)
    : host_(std::move(host)), port_(port), what_(std::move(what)) {
  if (host_ == "localhost") host_ = "127.0.0.1";
  in_addr parsed{};
  if (::inet_pton(AF_INET, host_.c_str(), &parsed) != 1)
    throw std::invalid_argument(what_ + ": '" + host_ +
                                "' is not an IPv4 address to listen on (127.0.0.1, localhost, 0.0.0.0 for every "
                                "interface, or one of this machine's addresses)");
}

UdpListener::~UdpListener() { stop(); }

void UdpListener::start(Handler handler) {
  if (thread_.joinable()) throw std::logic_error(what_ + " already listens on " + where());
  buffer_.resize(kUdpMaxDatagram);
  sender_.resize(sizeof(sockaddr_in));
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(what_ + ": cannot open a UDP socket: " + std::string(std::strerror(errno)));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port_);
  ::inet_pton(AF_INET, host_.c_str(), &address.sin_addr);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error(udp_bind_error(what_, where(), error));
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length);
  const int wake = ::eventfd(0, EFD_CLOEXEC);
  if (wake < 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error(what_ + ": cannot create an eventfd: " + std::string(std::strerror(error)));
  }
  socket_fd_ = fd;
  wake_fd_ = wake;
  bound_port_ = ntohs(bound.sin_port);
  handler_ = std::move(handler);
  thread_ = std::thread([this] { receive_loop(); });
}

void UdpListener::stop() noexcept {
  if (!thread_.joinable()) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
  thread_.join();
  ::close(socket_fd_);
  ::close(wake_fd_);
  socket_fd_ = wake_fd_ = -1;
}

std::string UdpListener::where() const { return host_ + ":" + std::to_string(bound_port_ != 0 ? bound_port_ : port_); }

std::string UdpListener::bound_address() const {
  if (socket_fd_ < 0) return "";
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  if (::getsockname(socket_fd_, reinterpret_cast<sockaddr*>(&bound), &length) != 0) return "";
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &bound.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(ntohs(bound.sin_port));
}

bool UdpListener::reply_to_sender(std::span<const std::uint8_t> datagram) noexcept {
  const ssize_t n = ::sendto(socket_fd_, datagram.data(), datagram.size(), MSG_DONTWAIT,
                             reinterpret_cast<const sockaddr*>(sender_.data()), sizeof(sockaddr_in));
  return n == static_cast<ssize_t>(datagram.size());
}

void UdpListener::receive_loop() noexcept {
  std::array<pollfd, 2> fds{pollfd{socket_fd_, POLLIN, 0}, pollfd{wake_fd_, POLLIN, 0}};
  for (;;) {
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents != 0) return;
    socklen_t length = sizeof(sockaddr_in);
    const ssize_t n = ::recvfrom(socket_fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(sender_.data()), &length);
    if (n < 0) continue;  // EAGAIN, or an ICMP error queued on the socket: nothing to read
    const std::int64_t arrived = monotonic_ns();
    handler_(std::span(buffer_.data(), static_cast<std::size_t>(n)), arrived);
  }
}

}  // namespace avar::inputs
