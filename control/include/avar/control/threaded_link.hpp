#pragma once
// Serves an ActuatorLink from its own I/O thread, fed through a latest-value mailbox, so that a
// slow or stalled link never delays the tick. send() only publishes the frame and wakes the
// thread; the thread sends the newest frame it finds (older ones are dropped). A watchdog counts
// the ticks since the thread last completed a send: past the limit, send() reports a timeout
// and the controller treats the link as failed.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "avar/control/frame_mailbox.hpp"
#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::control {

class ThreadedLink final : public firmware_iface::ActuatorLink {
 public:
  /// inner: the link to serve (borrowed; it must outlive this). frame_size: rig channel count.
  /// watchdog_ticks: sends in a row without a completed send before send() times out.
  ThreadedLink(firmware_iface::ActuatorLink& inner, std::size_t frame_size, std::uint32_t watchdog_ticks);
  /// Stops the thread (after finishing the send under way).
  ~ThreadedLink() override;
  ThreadedLink(const ThreadedLink&) = delete;
  ThreadedLink& operator=(const ThreadedLink&) = delete;

  /// Forwarded on the caller's thread; call before the loop starts.
  Status start() override;
  std::string start_problem() const override { return inner_.start_problem(); }
  Status read_positions(std::span<double> frame, std::span<bool> known) override;

  /// Publishes the frame for the I/O thread. Returns the status of the last completed send, or
  /// timeout when the watchdog expired. Real-time safe: no allocation, lock or wait.
  Status send(std::span<const double> frame) noexcept override;

  /// Asks the I/O thread to release the actuators (right after the send under way) and to send
  /// nothing more. Real-time safe.
  Status release() noexcept override;

  /// Forwarded at once: the inner link's flag is read by the I/O thread's next send.
  void release_channel(std::size_t channel) noexcept override { inner_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return inner_.saturated_pulses(); }
  const std::string& describe() const noexcept override { return inner_.describe(); }
  /// The newest telemetry the I/O thread brought back (through a second mailbox). Tick thread
  /// only; real-time safe.
  void read_telemetry(std::span<firmware_iface::ChannelTelemetry> out) const noexcept override;
  /// Forwarded: the inner link's counters are readable from any thread.
  firmware_iface::LinkCounters counters() const noexcept override { return inner_.counters(); }

  /// Sends the I/O thread completed.
  std::uint64_t completed_sends() const noexcept { return completions_.load(std::memory_order_acquire); }

 private:
  void serve();

  firmware_iface::ActuatorLink& inner_;
  FrameMailbox mailbox_;
  std::vector<double> io_frame_;  ///< I/O thread's copy
  mutable LatestFrameMailbox<firmware_iface::ChannelTelemetry> telemetry_mailbox_;  // reading is logically const
  std::vector<firmware_iface::ChannelTelemetry> io_telemetry_;  ///< I/O thread's copy
  mutable std::vector<firmware_iface::ChannelTelemetry> telemetry_;  ///< tick thread's newest
  std::uint32_t watchdog_ticks_;
  std::uint32_t ticks_without_completion_ = 0;  ///< tick thread only
  std::uint64_t last_seen_completions_ = 0;    ///< tick thread only
  std::atomic<bool> wake_{false};
  std::atomic<bool> stop_{false};
  std::atomic<bool> release_requested_{false};
  std::atomic<std::uint64_t> completions_{0};
  std::atomic<Status> last_status_{Status::ok};
  std::thread thread_;
};

}  // namespace avar::control
