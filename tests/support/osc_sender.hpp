#pragma once
// Sending OSC over loopback UDP in tests (liblo), and finding a free UDP port to listen on.

#include <arpa/inet.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace avar::testing {

/// A UDP socket bound to a free port of 127.0.0.1 (written to `port`); the caller closes it.
/// Throws std::runtime_error when there is none.
inline int bound_udp_socket(int& port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("no free UDP port on loopback");
  }
  port = ntohs(a.sin_port);
  return fd;
}

/// A UDP port on 127.0.0.1 that nothing listens on right now.
inline int free_udp_port() {
  int port = 0;
  ::close(bound_udp_socket(port));
  return port;
}

class OscSender {
 public:
  explicit OscSender(int port) : address_(lo_address_new("127.0.0.1", std::to_string(port).c_str())) {}
  ~OscSender() { lo_address_free(address_); }
  OscSender(const OscSender&) = delete;
  OscSender& operator=(const OscSender&) = delete;
  /// One message with one float argument; false when it could not be sent.
  bool send(const std::string& path, float value) { return lo_send(address_, path.c_str(), "f", value) >= 0; }
  /// For messages of other types (lo_send, lo_send_bundle).
  lo_address address() const { return address_; }

 private:
  lo_address address_;
};

}  // namespace avar::testing
