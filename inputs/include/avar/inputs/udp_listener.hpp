#pragma once
// A UDP socket bound to one IPv4 address (127.0.0.1 unless told otherwise) and a thread of its
// own that hands every datagram, stamped with CLOCK_MONOTONIC when recv() returned it, to a
// handler. For network inputs whose decoding is ours (Art-Net timecode, the OSC control surface).
//
// Threads: start/stop/bound_port from one thread; the handler runs on the listener's thread.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace avar::inputs {

class UdpListener {
 public:
  using Handler = std::function<void(std::span<const std::uint8_t> datagram, std::int64_t arrived_ns)>;

  /// `host`: dotted IPv4 ("0.0.0.0": every interface) or "localhost"; port 0: any free port.
  /// `what` names the input in errors ("Art-Net timecode"). Throws std::invalid_argument for a
  /// host that is neither. Opens nothing yet.
  UdpListener(std::string host, std::uint16_t port, std::string what);
  ~UdpListener();
  UdpListener(const UdpListener&) = delete;
  UdpListener& operator=(const UdpListener&) = delete;

  /// Binds and starts the thread. Throws std::runtime_error ("Art-Net timecode: cannot listen on
  /// 127.0.0.1:6454 (address in use: ...)"). Not real-time.
  void start(Handler handler);
  /// Joins the thread and closes the socket. Idempotent.
  void stop() noexcept;
  /// The port bound (the system's choice for port 0); 0 before start().
  std::uint16_t bound_port() const noexcept { return bound_port_; }
  /// "127.0.0.1:6454" (the bound port once started).
  std::string where() const;
  /// Where the socket is bound as the kernel says (getsockname), "127.0.0.1:9000"; "" when not
  /// listening.
  std::string bound_address() const;
  /// Sends `datagram` from the bound socket to the sender of the datagram being handled (state
  /// replies of a control surface). Handler thread only; false when it could not be sent.
  bool reply_to_sender(std::span<const std::uint8_t> datagram) noexcept;

 private:
  void receive_loop() noexcept;

  std::string host_;
  std::uint16_t port_;
  std::string what_;
  std::uint16_t bound_port_ = 0;
  int socket_fd_ = -1;
  int wake_fd_ = -1;  ///< eventfd: stop() wakes the thread's poll
  Handler handler_;
  std::vector<std::uint8_t> buffer_;  ///< one datagram, the thread's
  std::vector<std::uint8_t> sender_;  ///< the sockaddr of the datagram being handled
  std::thread thread_;
};

}  // namespace avar::inputs
