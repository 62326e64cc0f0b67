#pragma once
// A CAN bus as the control loop sees it: one ActuatorLink over one FrameTransport (SocketCAN, an
// SLCAN adapter, a simulated bus) running one drive set per drive protocol on that bus (ODrive,
// CiA 402, MIT: CanDrives). Per send(): frames already received (heartbeats, late replies) are
// offered to the drive sets, each set adds its tick's frames, all go out in one send, then the
// replies are collected until every set has its own or the reply deadline passes, and each set
// judges its tick. A drive that falls silent or faults is a channel fault through telemetry
// (kDeviceLost, kDeviceFaultState), named by channel_problem(); only a failed link (bus-off, the
// adapter gone) makes send() fail, after which the link reopens now and then.
//
// Threads: one thread (the link's I/O thread) calls start, read_positions, send and release;
// release_channel, saturated and counters from any thread. send() and release() are real-time
// safe but for the rare reopen after a failure.

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/atomic_link_counters.hpp"
#include "avar/firmware_iface/can_drives.hpp"
#include "avar/firmware_iface/can_outbox.hpp"
#include "avar/firmware_iface/frame_transport.hpp"
#include "avar/firmware_iface/reconnector.hpp"

namespace avar::firmware_iface {

struct CanLinkConfig {
  /// Longest a tick waits for the drives' replies, on the transport's clock.
  std::chrono::milliseconds reply_timeout{5};
  /// While the bus is lost, send() reopens it every this many calls.
  std::uint32_t reconnect_every = 10;
  /// For messages: "CAN bus 'arm' (SLCAN on /dev/ttyACM0)".
  std::string description;
};

/// What the link measured of its bus, for benchmarks and diagnostics.
struct CanLinkStats {
  std::uint64_t frames_sent = 0;     ///< by this link's send() and release()
  std::uint64_t frames_taken = 0;    ///< received frames a drive set used
  std::uint64_t frames_ignored = 0;  ///< received frames no drive set wanted
  std::uint64_t bits_sent = 0;       ///< worst-case wire bits of the frames sent (can_frame_bits)
  std::uint64_t bits_received = 0;   ///< worst-case wire bits of the frames received
  std::uint64_t error_frames = 0;
};

class CanLink final : public ActuatorLink {
 public:
  /// `drives`: one set per drive protocol on the bus, none empty. Takes ownership of both.
  CanLink(std::unique_ptr<FrameTransport> transport, std::vector<std::unique_ptr<CanDrives>> drives, CanLinkConfig config);

  Status start() override;
  std::string start_problem() const override { return start_problem_; }
  std::string channel_problem(std::size_t channel) const override;
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  Status send(std::span<const double> frame) noexcept override;
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override;
  const std::string& describe() const noexcept override { return config_.description; }
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept override;
  LinkCounters counters() const noexcept override;

  /// On the link's thread.
  const CanLinkStats& stats() const noexcept { return stats_; }
  FrameTransport& transport() noexcept { return *transport_; }

 private:
  /// Offers one received frame to the drive sets; false for a bus-off error frame.
  bool dispatch(const CanFrame& frame) noexcept;
  /// Takes every frame already received, without waiting. io_error on bus-off or failure.
  Status drain() noexcept;
  /// Waits for the sets' replies until the reply deadline. io_error on bus-off or failure.
  Status collect() noexcept;
  bool replies_complete() const noexcept;
  /// Sends the outbox; marks the link lost on an I/O error.
  Status flush() noexcept;

  std::unique_ptr<FrameTransport> transport_;
  std::vector<std::unique_ptr<CanDrives>> drives_;
  CanLinkConfig config_;
  CanOutbox outbox_;
  Reconnector reconnector_;
  AtomicLinkCounters counters_;
  CanLinkStats stats_;
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
