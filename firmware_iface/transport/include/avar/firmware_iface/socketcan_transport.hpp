#pragma once
// FrameTransport over a Linux SocketCAN interface (can0, a USB adapter with a kernel driver, or
// vcan0): a raw AF_CAN socket bound by interface name, with the controller's error frames
// switched on (CAN_RAW_ERR_FILTER) and mapped to CanErrorClass. The bitrate is the interface's
// own set-up (`sudo ip link set can0 type can bitrate 1000000 restart-ms 100 && sudo ip link set
// can0 up`); the constructor is told it for the frame arithmetic.
//
// Clock: now() is steady_clock; deadlines are waited for with poll(). A frame's timestamp is the
// kernel's receive time (SO_TIMESTAMP, on the realtime clock) carried onto steady_clock: the
// steady time of its reading minus how long ago, on the realtime clock, the kernel received it.
//
// Threads: one thread uses the transport; counters() from any thread. Real-time: send, receive,
// now and discard_input allocate nothing and throw nothing.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/atomic_frame_counters.hpp"
#include "avar/firmware_iface/frame_transport.hpp"

struct can_frame;

namespace avar::firmware_iface {

/// A receive filter: frames whose identifier matches `id` in the bits of `mask` pass.
struct SocketCanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = kCanMaxStandardId;
  bool extended = false;  ///< matches extended (29-bit) frames instead of standard ones
};

struct SocketCanConfig {
  /// Frames with any other identifier are dropped by the kernel; empty: every frame passes.
  /// Error frames always pass.
  std::vector<SocketCanFilter> filters;
  /// How long send() waits for room in a full transmit queue before it gives up with timeout.
  std::chrono::milliseconds send_timeout{5};
};

class SocketCanTransport final : public FrameTransport {
 public:
  /// Opens a raw CAN socket on `interface` (bitrate in bit/s, as the interface is set up).
  /// Throws InputError naming the interface, with how to check or create it, when the kernel
  /// has no CAN support, the interface is missing or not a CAN interface, or it is down. Not
  /// real-time.
  SocketCanTransport(const std::string& interface, int bitrate, SocketCanConfig config = {});
  ~SocketCanTransport() override;
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  /// One write per frame; io_error when the interface is down or the controller is bus-off,
  /// timeout when the transmit queue stayed full for send_timeout, out_of_range for an invalid
  /// or error frame (nothing sent).
  Status send(std::span<const CanFrame> frames) noexcept override;
  Status receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept override;
  std::chrono::nanoseconds now() const noexcept override;
  void discard_input() noexcept override;
  /// Closes and opens the socket again. The controller itself restarts after a bus-off when the
  /// interface has restart-ms set (or `ip link set can0 type can restart`).
  Status reopen() noexcept override;
  int bitrate() const noexcept override { return bitrate_; }
  FrameCounters counters() const noexcept override { return counters_.snapshot(); }
  /// The interface name ("can0").
  const std::string& name() const noexcept override { return interface_; }

 private:
  /// Opens and binds fd_; throws InputError naming the interface.
  void open_socket();

  std::string interface_;
  int bitrate_;
  SocketCanConfig config_;
  int fd_ = -1;
  AtomicFrameCounters counters_;
};

/// Conversions between CanFrame and the kernel's struct can_frame. Pure, real-time safe.
namespace socketcan {

/// The CanErrorClass bits of a kernel error frame (CAN_ERR_FLAG set): its class bits in
/// can_id and the controller details in data[1] (CAN_ERR_CRTL_*).
std::uint32_t error_classes(std::uint32_t can_id, const std::uint8_t* data, std::uint8_t dlc) noexcept;
/// A kernel frame as a CanFrame (an error frame: id = CanErrorClass bits, the kernel's data
/// bytes kept, counters in data[6] TX and data[7] RX).
CanFrame from_kernel(const ::can_frame& k) noexcept;
/// A CanFrame for the kernel; false for an invalid or error frame.
bool to_kernel(const CanFrame& f, ::can_frame* k) noexcept;

}  // namespace socketcan

}  // namespace avar::firmware_iface
