#pragma once
// `avar play ... --osc-control [ADDR:]PORT`: an OSC control surface over UDP (bound to 127.0.0.1
// unless an address is given). With it the show waits at its first frame (after the soft start)
// until told to play:
//   /avar/show/play NAME    play the loaded show (NAME must be its name)
//   /avar/show/stop         ease to rest and end the run (as Ctrl-C)
//   /avar/show/seek SECONDS move show time there (the limiter turns the jump into motion)
//   /avar/estop             latch an e-stop fault: every actuator takes its fail-safe action
//   /avar/state             ask for the state
// Every message gets a reply to its sender: /avar/state ,sfs PHASE SHOW_TIME SHOW_NAME (phase:
// disabled, homing, waiting, running, stopping, faulted), or /avar/error ,s WHY for a message that
// was not understood (counted, ignored: the show goes on).
//
// Threads: the listener's thread decodes and replies; the loop reads the requests through atomics
// (ShowClock::read and the e-stop flag), real-time safe.

#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "avar/control/runner.hpp"
#include "avar/control/show_clock.hpp"
#include "avar/inputs/udp_listener.hpp"

namespace avar::session {

/// "9000", "127.0.0.1:9000", "0.0.0.0:9000" -> host and port; std::invalid_argument otherwise.
std::pair<std::string, std::uint16_t> parse_osc_control_address(const std::string& text);

class OscControlSurface final : public control::ShowClock, public control::TickObserver {
 public:
  /// Nothing is bound yet. Throws std::invalid_argument for a malformed address.
  OscControlSurface(const std::string& address, std::string show_name);
  ~OscControlSurface() override;

  /// Binds and listens (std::runtime_error when the address cannot be bound).
  void start();
  void stop() noexcept;
  std::uint16_t bound_port() const noexcept { return listener_.bound_port(); }
  std::string where() const { return listener_.where(); }

  /// The e-stop flag for RunOptions::estop_remote.
  const std::atomic<bool>& estop() const noexcept { return estop_; }

  control::ShowClockReading read(double now_s) noexcept override;
  void forward_to(control::TickObserver& inner) { inner_ = &inner; }
  void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) override;

  /// Commands taken and messages ignored, for the summary.
  void summarize(std::ostream& out) const;

 private:
  void handle(std::span<const std::uint8_t> datagram) noexcept;
  void reply_state() noexcept;
  void reply_error(const std::string& why) noexcept;
  /// Serialises the lo_message `message` at `path`, sends it to the sender, frees it.
  void send_reply(void* message, const char* path) noexcept;

  inputs::UdpListener listener_;
  std::string show_name_;
  control::TickObserver* inner_ = nullptr;
  // Requests, OSC thread -> loop.
  std::atomic<bool> play_{false};
  std::atomic<bool> stop_{false};
  std::atomic<bool> estop_{false};
  std::atomic<std::uint64_t> seek_requests_{0};
  std::atomic<double> seek_to_{0};
  // State, loop -> OSC thread.
  std::atomic<int> phase_{0};  ///< control::Phase, or -1: running but waiting for play
  std::atomic<double> show_time_{0};
  // Loop-only.
  std::uint64_t seeks_seen_ = 0;
  bool started_ = false;
  double base_show_s_ = 0;
  double base_now_s_ = 0;
  // Counters (OSC thread writes, summary reads after stop).
  std::atomic<std::uint64_t> commands_{0};
  std::atomic<std::uint64_t> ignored_{0};
};

}  // namespace avar::session
