#pragma once
// A FrameTransport on a simulated CAN bus (SimCanBus), in memory, deterministic, on the bus's
// simulated clock in the caller's thread, in the style of SimWire: send() puts frames on the
// bus and the clock moves by their wire time (nodes advance by it, and their own frames are
// arbitrated in between); receive() runs the bus, advancing the nodes, until a frame for the
// host arrives or the deadline (the clock then at the deadline). Measures what a drive set's
// tick costs on a real bus of that bitrate. For tests and benchmarks.
//
// Threads: one thread uses the transport and the bus; counters() from any thread. send and
// receive allocate nothing.

#include <chrono>
#include <string>

#include "avar/firmware_iface/atomic_frame_counters.hpp"
#include "avar/firmware_iface/frame_transport.hpp"
#include "avar/sim/sim_can_bus.hpp"

namespace avar::sim {

class SimCanTransport final : public firmware_iface::FrameTransport {
 public:
  /// The bus is borrowed and must outlive this; it is the host port's only user.
  /// max_send_wait_s: how long send() lets the bus run before it gives up on frames that lose
  /// arbitration every time (timeout).
  explicit SimCanTransport(SimCanBus& bus, std::string name = "simulated CAN bus", double max_send_wait_s = 0.1);

  /// ok once every frame is off the wire; io_error while bus-off; out_of_range for an invalid or
  /// error frame (nothing sent); timeout when they were not all sent within max_send_wait_s.
  Status send(std::span<const firmware_iface::CanFrame> frames) noexcept override;
  Status receive(firmware_iface::CanFrame* frame, std::chrono::nanoseconds deadline) noexcept override;
  /// The bus clock.
  std::chrono::nanoseconds now() const noexcept override { return to_nanoseconds(bus_.now_s()); }
  void discard_input() noexcept override { bus_.host_discard(); }
  /// Restarts the host's controller after a bus-off and drops what was received.
  Status reopen() noexcept override;
  int bitrate() const noexcept override { return bus_.bitrate(); }
  firmware_iface::FrameCounters counters() const noexcept override { return counters_.snapshot(); }
  const std::string& name() const noexcept override { return name_; }

  /// Simulated seconds on the bus clock.
  double now_s() const noexcept { return bus_.now_s(); }
  /// Frames, bits and busy time the bus carried (every sender's), and its load.
  SimCanBusStatistics statistics() const noexcept { return bus_.statistics(); }
  SimCanBus& bus() noexcept { return bus_; }

  /// Bytes a frame counts for in FrameCounters::bytes_sent/received (a SocketCAN can_frame).
  static constexpr std::uint64_t kBytesPerFrame = 16;

 private:
  static std::chrono::nanoseconds to_nanoseconds(double s) noexcept;

  SimCanBus& bus_;
  std::string name_;
  double max_send_wait_s_;
  firmware_iface::AtomicFrameCounters counters_;
};

}  // namespace avar::sim
