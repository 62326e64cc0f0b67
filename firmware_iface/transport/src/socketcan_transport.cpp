#include "avar/firmware_iface/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "avar/core/input_error.hpp"
#include "avar/core/monotonic_clock.hpp"

namespace avar::firmware_iface {
namespace socketcan {

std::uint32_t error_classes(std::uint32_t can_id, const std::uint8_t* data, std::uint8_t dlc) noexcept {
  std::uint32_t classes = 0;
  if (can_id & CAN_ERR_BUSOFF) classes |= kCanErrorBusOff;
  if (can_id & CAN_ERR_RESTARTED) classes |= kCanErrorRestarted;
  if (can_id & CAN_ERR_ACK) classes |= kCanErrorAck;
  if (can_id & (CAN_ERR_PROT | CAN_ERR_BUSERROR | CAN_ERR_TRX)) classes |= kCanErrorProtocol;
  if ((can_id & CAN_ERR_CRTL) && dlc > 1) {
    const std::uint8_t crtl = data[1];
    if (crtl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) classes |= kCanErrorOverrun;
    if (crtl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) classes |= kCanErrorWarning;
    if (crtl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) classes |= kCanErrorPassive;
  }
  return classes;
}

CanFrame from_kernel(const ::can_frame& k) noexcept {
  CanFrame f;
  f.dlc = std::min<std::uint8_t>(k.len, kCanMaxData);
  std::copy_n(k.data, f.dlc, f.data.begin());
  if (k.can_id & CAN_ERR_FLAG) {
    f.error = true;
    f.id = error_classes(k.can_id & CAN_ERR_MASK, k.data, f.dlc);
    return f;
  }
  f.extended = (k.can_id & CAN_EFF_FLAG) != 0;
  f.rtr = (k.can_id & CAN_RTR_FLAG) != 0;
  f.id = k.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  return f;
}

bool to_kernel(const CanFrame& f, ::can_frame* k) noexcept {
  if (f.error || !can_frame_valid(f)) return false;
  std::memset(k, 0, sizeof(*k));
  k->can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0u) | (f.rtr ? CAN_RTR_FLAG : 0u);
  k->len = f.dlc;
  const auto payload = f.payload();
  std::copy(payload.begin(), payload.end(), k->data);
  return true;
}

}  // namespace socketcan

namespace {

std::string how_to_check(const std::string& interface) {
  return "check it with `ip link show " + interface + "`; a real adapter: `sudo ip link set " + interface +
         " type can bitrate 1000000 restart-ms 100 && sudo ip link set " + interface +
         " up`; a virtual one: `sudo modprobe vcan && sudo ip link add dev " + interface + " type vcan && sudo ip link set up " +
         interface + "`";
}

std::chrono::nanoseconds steady_now() noexcept { return std::chrono::nanoseconds(monotonic_ns()); }

}  // namespace

SocketCanTransport::SocketCanTransport(const std::string& interface, int bitrate, SocketCanConfig config)
    : interface_(interface), bitrate_(bitrate), config_(std::move(config)) {
  open_socket();
}

SocketCanTransport::~SocketCanTransport() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCanTransport::open_socket() {
  const auto fail = [&](const std::string& problem) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw InputError({interface_, 0, 0}, problem);
  };
  if (interface_.empty() || interface_.size() >= IFNAMSIZ)
    fail("not a network interface name (expected one such as can0 or vcan0)");
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0)
    fail(std::string("cannot open a CAN socket: ") + std::strerror(errno) +
         " (this kernel has no SocketCAN support: `sudo modprobe can_raw`); " + how_to_check(interface_));
  const unsigned index = ::if_nametoindex(interface_.c_str());
  if (index == 0) fail("no such CAN interface; " + how_to_check(interface_));

  ifreq request{};
  std::strncpy(request.ifr_name, interface_.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, SIOCGIFFLAGS, &request) == 0 && !(request.ifr_flags & IFF_UP))
    fail("the CAN interface is down; bring it up: `sudo ip link set " + interface_ + " up` (" + how_to_check(interface_) + ")");

  const can_err_mask_t errors = CAN_ERR_MASK;
  const int on = 1;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors)) != 0 ||
      ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof(on)) != 0)
    fail(std::string("cannot set up the CAN socket: ") + std::strerror(errno));
  if (!config_.filters.empty()) {
    std::vector<can_filter> filters;
    for (const SocketCanFilter& f : config_.filters)
      filters.push_back({f.id | (f.extended ? CAN_EFF_FLAG : 0u), f.mask | CAN_EFF_FLAG});
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                     static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0)
      fail(std::string("cannot set the CAN receive filters: ") + std::strerror(errno));
  }

  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0)
    fail(std::string("cannot bind a CAN socket to it: ") + std::strerror(errno) + " (is it a CAN interface?); " +
         how_to_check(interface_));
}

std::chrono::nanoseconds SocketCanTransport::now() const noexcept { return steady_now(); }

Status SocketCanTransport::send(std::span<const CanFrame> frames) noexcept {
  if (fd_ < 0) return Status::io_error;
  for (const CanFrame& f : frames)
    if (f.error || !can_frame_valid(f)) return Status::out_of_range;
  for (const CanFrame& f : frames) {
    ::can_frame k{};
    (void)socketcan::to_kernel(f, &k);
    const auto give_up = steady_now() + config_.send_timeout;
    for (;;) {
      const ssize_t n = ::write(fd_, &k, sizeof(k));
      if (n == static_cast<ssize_t>(sizeof(k))) break;
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == ENOBUFS)) {
        // The transmit queue is full: wait for room, at most until send_timeout.
        const auto left = std::chrono::ceil<std::chrono::milliseconds>(give_up - steady_now());
        if (left.count() <= 0) return Status::timeout;
        pollfd p{fd_, POLLOUT, 0};
        (void)::poll(&p, 1, static_cast<int>(left.count()));
        continue;
      }
      return Status::io_error;  // ENETDOWN (interface down, bus-off) and the like
    }
    counters_.add(&FrameCounters::frames_sent);
    counters_.add(&FrameCounters::bytes_sent, sizeof(k));
  }
  return Status::ok;
}

Status SocketCanTransport::receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept {
  if (fd_ < 0) return Status::io_error;
  for (;;) {
    ::can_frame k{};
    iovec io{&k, sizeof(k)};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval))];
    msghdr message{};
    message.msg_iov = &io;
    message.msg_iovlen = 1;
    message.msg_control = control;
    message.msg_controllen = sizeof(control);
    const ssize_t n = ::recvmsg(fd_, &message, 0);
    if (n == static_cast<ssize_t>(sizeof(k))) {
      const std::chrono::nanoseconds read_at = steady_now();
      *frame = socketcan::from_kernel(k);
      frame->timestamp = read_at;
      for (cmsghdr* c = CMSG_FIRSTHDR(&message); c; c = CMSG_NXTHDR(&message, c)) {
        if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_TIMESTAMP) continue;
        timeval kernel{};
        std::memcpy(&kernel, CMSG_DATA(c), sizeof(kernel));
        timeval real{};
        ::gettimeofday(&real, nullptr);
        const auto ago =
            std::chrono::seconds(real.tv_sec - kernel.tv_sec) + std::chrono::microseconds(real.tv_usec - kernel.tv_usec);
        if (ago.count() > 0) frame->timestamp = read_at - std::chrono::duration_cast<std::chrono::nanoseconds>(ago);
      }
      count_received(counters_, *frame);
      counters_.add(&FrameCounters::bytes_received, sizeof(k));
      return Status::ok;
    }
    if (n >= 0) {  // a short frame: not a classic CAN frame
      counters_.add(&FrameCounters::malformed);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) return Status::io_error;
    const std::chrono::nanoseconds now = steady_now();
    if (now >= deadline) return Status::timeout;
    pollfd p{fd_, POLLIN, 0};
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - now);
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno != EINTR) return Status::io_error;
    if (ready > 0 && (p.revents & (POLLERR | POLLNVAL)) && !(p.revents & POLLIN)) return Status::io_error;
  }
}

void SocketCanTransport::discard_input() noexcept {
  if (fd_ < 0) return;
  ::can_frame k{};
  while (::recv(fd_, &k, sizeof(k), MSG_DONTWAIT) > 0) {
  }
}

Status SocketCanTransport::reopen() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  try {
    open_socket();
    return Status::ok;
  } catch (...) {
    return Status::io_error;
  }
}

}  // namespace avar::firmware_iface
