#pragma once
// The CAN half of the transport layer: moves whole frames with deadlines and knows nothing of
// drives. Implementations: SocketCanTransport (raw AF_CAN socket), SlcanTransport (an SLCAN
// adapter over any ByteTransport), and sim::SimCanTransport (an in-memory bus on a simulated
// clock). Threads: one thread uses a transport; counters() from any thread.

#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface {

/// What a frame transport has seen since it was opened; counters only grow.
struct FrameCounters {
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_received = 0;  ///< data and remote frames (error frames not included)
  std::uint64_t error_frames = 0;     ///< error frames the controller reported
  std::uint64_t bus_off = 0;          ///< times the controller went bus-off
  std::uint64_t bytes_sent = 0;       ///< on the host link: SLCAN text, SocketCAN struct can_frame
  std::uint64_t bytes_received = 0;
  std::uint64_t malformed = 0;  ///< received input that did not decode (SLCAN noise), skipped
};

class FrameTransport {
 public:
  virtual ~FrameTransport() = default;

  /// Queues every frame of `frames` for transmission, in order. ok once all were handed to the
  /// controller; io_error when the link failed (bus-off, adapter gone); timeout when the
  /// controller's transmit queue stayed full. Real-time safe: no allocation, no exception.
  virtual Status send(std::span<const CanFrame> frames) noexcept = 0;

  /// Waits for the next received frame (data, remote or error) until `deadline` on now()'s clock.
  /// ok with *frame filled (its timestamp set); timeout when none came in time; io_error when the
  /// link failed. Real-time safe.
  virtual Status receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept = 0;

  /// Now on the transport's own clock (monotonic for real links, simulated time for a simulated
  /// bus). Drivers take every deadline from here. Real-time safe.
  virtual std::chrono::nanoseconds now() const noexcept = 0;

  /// Drops every frame received and not yet taken (stale replies).
  virtual void discard_input() noexcept = 0;

  /// Closes and opens the link again after a failure (bus-off recovery, an adapter plugged back
  /// in); ok once it is usable. Not real-time: call from the link's I/O thread, never the tick.
  virtual Status reopen() noexcept = 0;

  /// The bus bitrate in bit/s (what the frame arithmetic assumes).
  virtual int bitrate() const noexcept = 0;

  /// Any thread.
  virtual FrameCounters counters() const noexcept = 0;

  /// For messages: "can0", "SLCAN on /dev/ttyACM0", "simulated CAN bus".
  virtual const std::string& name() const noexcept = 0;
};

}  // namespace avar::firmware_iface
