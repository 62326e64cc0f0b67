#pragma once
// OSC over UDP as named controls (addresses and values: osc_dispatch.hpp). Listens on one IPv4
// address, 127.0.0.1 unless told otherwise: another machine reaches it only when started with
// "0.0.0.0" (every interface) or one of this machine's addresses.
//
// liblo 0.31 cannot bind its servers to an address (they listen on every interface; the host of
// lo_server_new_from_url is taken as a multicast group), so the socket and its thread are ours and
// liblo decodes the datagrams (lo_message_deserialise). Bundles are unpacked and their messages
// applied at once (their time tags are not waited for).
//
// Threads: one thread of its own receives, decodes and posts, stamping each datagram with
// CLOCK_MONOTONIC when recv() returned it. start/stop/describe/bound_port from one thread;
// counters() from any.

#include <cstdint>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "avar/inputs/atomic_input_counters.hpp"
#include "avar/inputs/input_source.hpp"
#include "avar/inputs/udp_listener.hpp"

namespace avar::inputs {

/// Decodes one UDP datagram (a message, or a bundle of messages and bundles nested up to 8 deep)
/// and posts each message's control into `sink`. Returns the messages taken and ignored (an
/// undecodable datagram or bundle element counts as one ignored message). Allocates (liblo);
/// never throws; any thread.
InputCounters dispatch_osc_packet(std::span<const std::uint8_t> packet, ControlSink& sink, std::int64_t arrived_ns) noexcept;

class OscInput final : public InputSource {
 public:
  /// `host`: the IPv4 address to listen on ("127.0.0.1"; "0.0.0.0": every interface) or
  /// "localhost"; `port` 0: any free port (bound_port() tells which after start()). Throws
  /// std::invalid_argument for a host that is neither. Opens nothing yet.
  explicit OscInput(std::string host = "127.0.0.1", std::uint16_t port = 9000);
  ~OscInput() override;
  OscInput(const OscInput&) = delete;
  OscInput& operator=(const OscInput&) = delete;

  /// Binds the socket and starts the thread. Throws std::runtime_error ("OSC: cannot listen on
  /// 127.0.0.1:9000 (address in use: ...)") when the address cannot be bound. A second start()
  /// while running is a no-op with the same sink and throws std::logic_error with another; after
  /// stop(), start() listens again. Not real-time.
  void start(ControlSink& sink) override;
  void stop() noexcept override;
  /// "OSC on udp 127.0.0.1:9000" (the bound port once started on port 0).
  std::string describe() const override;
  InputCounters counters() const noexcept override { return counters_.snapshot(); }

  /// The port listened on: the one asked for, or the one the system chose for port 0 (0 before
  /// the first start()).
  std::uint16_t bound_port() const noexcept { return listener_.bound_port(); }
  /// Where the socket is bound as the kernel says (getsockname), "127.0.0.1:9000"; "" when not
  /// listening.
  std::string bound_address() const;

 private:
  UdpListener listener_;
  bool listening_ = false;
  ControlSink* sink_ = nullptr;
  AtomicInputCounters counters_;
};

}  // namespace avar::inputs
