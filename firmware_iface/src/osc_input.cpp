#include "avar/firmware_iface/osc_input.hpp"

#include <arpa/inet.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "avar/firmware_iface/osc_dispatch.hpp"

namespace avar::firmware_iface {
namespace {

constexpr int kMaxBundleDepth = 8;
constexpr std::size_t kBundleHeaderSize = 16;  // "#bundle\0" and a time tag
constexpr std::size_t kMaxArguments = 4;       // more is ignored anyway: controls take one
constexpr std::size_t kMaxDatagram = 65536;

std::uint32_t read_be32(const std::uint8_t* p) noexcept {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

bool is_bundle(std::span<const std::uint8_t> data) noexcept {
  static constexpr char kTag[8] = {'#', 'b', 'u', 'n', 'd', 'l', 'e', '\0'};
  return data.size() >= sizeof kTag && std::memcmp(data.data(), kTag, sizeof kTag) == 0;
}

/// liblo's argument pointers are only 4-byte aligned (lo_arg is a union with 8-byte members):
/// read the value's bytes, never through the union.
template <class T>
T read_arg(const lo_arg* arg) noexcept {
  T value;
  std::memcpy(&value, arg, sizeof value);
  return value;
}

double number_of(char type, const lo_arg* arg) noexcept {
  switch (type) {
    case LO_FLOAT: return read_arg<float>(arg);
    case LO_DOUBLE: return read_arg<double>(arg);
    case LO_INT32: return read_arg<std::int32_t>(arg);
    case LO_INT64: return static_cast<double>(read_arg<std::int64_t>(arg));
    default: return 0.0;
  }
}

/// Whether one message set a control.
bool dispatch_message(std::span<const std::uint8_t> data, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  if (data.empty()) return false;
  int result = 0;
  // lo_message_deserialise copies the data before it swaps bytes: the const_cast writes nothing.
  void* bytes = const_cast<std::uint8_t*>(data.data());
  lo_message message = lo_message_deserialise(bytes, data.size(), &result);
  if (message == nullptr) return false;
  bool set = false;
  const char* path = lo_get_path(bytes, static_cast<ssize_t>(data.size()));
  const char* types = lo_message_get_types(message);
  const auto argc = static_cast<std::size_t>(lo_message_get_argc(message));
  if (path != nullptr && types != nullptr && argc <= kMaxArguments) {
    lo_arg** argv = lo_message_get_argv(message);
    std::array<double, kMaxArguments> values{};
    for (std::size_t i = 0; i < argc; ++i) values[i] = number_of(types[i], argv[i]);
    if (const auto control = osc_control(path, std::string_view(types, argc), std::span(values.data(), argc))) {
      sink.post(control->control, control->value, false, arrived_ns);
      set = true;
    }
  }
  lo_message_free(message);
  return set;
}

void dispatch_element(std::span<const std::uint8_t> data, ControlSink& sink, std::int64_t arrived_ns, int depth,
                      InputCounters& counters) noexcept {
  const auto ignore_one = [&] { ++counters.messages, ++counters.ignored; };
  if (!is_bundle(data)) {
    ++counters.messages;
    if (!dispatch_message(data, sink, arrived_ns)) ++counters.ignored;
    return;
  }
  if (depth >= kMaxBundleDepth || data.size() < kBundleHeaderSize) return ignore_one();
  std::size_t at = kBundleHeaderSize;
  while (at < data.size()) {
    if (data.size() - at < 4) return ignore_one();
    const std::uint32_t size = read_be32(&data[at]);
    at += 4;
    if (size > data.size() - at) return ignore_one();
    dispatch_element(data.subspan(at, size), sink, arrived_ns, depth + 1, counters);
    at += size;
  }
}

std::string listen_error(const std::string& where, int error) {
  std::string why;
  switch (error) {
    case EADDRINUSE: why = "address in use: another program, or another avar, listens there"; break;
    case EADDRNOTAVAIL: why = "no interface of this machine has that address"; break;
    case EACCES: why = "ports below 1024 need privileges"; break;
    default: why = std::strerror(error);
  }
  return "OSC: cannot listen on " + where + " (" + why + ")";
}

std::string address_text(const sockaddr_in& a) {
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(ntohs(a.sin_port));
}

}  // namespace

InputCounters dispatch_osc_packet(std::span<const std::uint8_t> packet, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  InputCounters counters;
  dispatch_element(packet, sink, arrived_ns, 0, counters);
  return counters;
}

OscInput::OscInput(std::string host, std::uint16_t port) : host_(std::move(host)), port_(port) {
  if (host_ == "localhost") host_ = "127.0.0.1";
  in_addr parsed{};
  if (::inet_pton(AF_INET, host_.c_str(), &parsed) != 1)
    throw std::invalid_argument("OSC: '" + host_ +
                                "' is not an IPv4 address to listen on (127.0.0.1, localhost, 0.0.0.0 for every "
                                "interface, or one of this machine's addresses)");
}

OscInput::~OscInput() { stop(); }

void OscInput::start(ControlSink& sink) {
  if (thread_.joinable()) {
    if (sink_ == &sink) return;
    throw std::logic_error(describe() + " already delivers into another sink");
  }
  buffer_.resize(kMaxDatagram);
  const std::string where = host_ + ":" + std::to_string(port_);
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error("OSC: cannot open a UDP socket: " + std::string(std::strerror(errno)));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port_);
  ::inet_pton(AF_INET, host_.c_str(), &address.sin_addr);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error(listen_error(where, error));
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length);
  const int wake = ::eventfd(0, EFD_CLOEXEC);
  if (wake < 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error("OSC: cannot create an eventfd: " + std::string(std::strerror(error)));
  }
  socket_fd_ = fd;
  wake_fd_ = wake;
  bound_port_ = ntohs(bound.sin_port);
  sink_ = &sink;
  thread_ = std::thread([this] { receive_loop(); });
}

void OscInput::stop() noexcept {
  if (!thread_.joinable()) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
  thread_.join();
  ::close(socket_fd_);
  ::close(wake_fd_);
  socket_fd_ = wake_fd_ = -1;
}

void OscInput::receive_loop() noexcept {
  std::array<pollfd, 2> fds{pollfd{socket_fd_, POLLIN, 0}, pollfd{wake_fd_, POLLIN, 0}};
  for (;;) {
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents != 0) return;
    const ssize_t n = ::recv(socket_fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT);
    if (n < 0) continue;  // EAGAIN, or an ICMP error queued on the socket: nothing to read
    const std::int64_t arrived = input_arrival_now_ns();
    counters_.add(dispatch_osc_packet(std::span(buffer_.data(), static_cast<std::size_t>(n)), *sink_, arrived));
  }
}

std::string OscInput::describe() const {
  return "OSC on udp " + host_ + ":" + std::to_string(bound_port_ != 0 ? bound_port_ : port_);
}

std::string OscInput::bound_address() const {
  if (socket_fd_ < 0) return "";
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  if (::getsockname(socket_fd_, reinterpret_cast<sockaddr*>(&bound), &length) != 0) return "";
  return address_text(bound);
}

}  // namespace avar::firmware_iface
