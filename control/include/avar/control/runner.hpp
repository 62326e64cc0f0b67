#pragma once
// Runs a Controller tick after tick, on real time (absolute-deadline sleeps on CLOCK_MONOTONIC)
// or on a stepped simulated clock (as fast as the machine goes, deterministic). The runner is
// the only place that reads a clock; everything below it gets the tick time as an argument.

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/latency_histogram.hpp"
#include "avar/control/plant.hpp"
#include "avar/control/realtime_setup.hpp"

namespace avar::control {

enum class ClockMode { realtime, stepped };

struct RunOptions {
  double rate_hz = 50;  ///< ticks per second
  ClockMode clock = ClockMode::realtime;
  RealtimeRequest realtime;  ///< scheduling for the loop thread (real-time clock only)
  /// More deadline misses than this in one run is a fault.
  std::uint64_t deadline_miss_budget = UINT64_MAX;
  /// The e-stop input: when it reads true the controller faults (nullptr: none).
  const std::atomic<bool>* estop = nullptr;
  /// A second e-stop, watched the same way (the rig's GPIO e-stop input beside the keyboard's;
  /// nullptr: none).
  const std::atomic<bool>* estop_input = nullptr;
  /// A third, from a remote control surface (OSC /avar/estop; nullptr: none).
  const std::atomic<bool>* estop_remote = nullptr;
  /// The simulated figure, advanced by each tick's period after the tick (nullptr: none).
  Plant* plant = nullptr;
};

/// Called after every tick (and the plant's step), on the loop thread: statistics, traces,
/// progress. after_tick only watches: nothing in the loop depends on it; before_tick is where
/// an owner of the loop (a show session) hands the controller its commands. Implementations on
/// a real-time loop must be quick.
class TickObserver {
 public:
  virtual ~TickObserver() = default;
  /// lateness_s: how late this tick's wake-up came after its deadline (0 on the stepped clock).
  virtual void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, Controller& controller) = 0;
  /// Called before every tick, after the runner's own interrupt and e-stop checks, on the loop
  /// thread: the place to hand the controller commands taken from other threads (a show
  /// session's queue). Must be real-time safe. Does nothing unless overridden.
  virtual void before_tick(std::uint64_t tick, double now_s, Controller& controller) noexcept {
    (void)tick, (void)now_s, (void)controller;
  }
};

struct [[nodiscard]] RunResult {
  std::uint64_t ticks = 0;
  std::uint64_t deadline_misses = 0;  ///< ticks whose work ended after the next deadline
  LatencyHistogram lateness;          ///< wake-up lateness after each deadline (realtime only)
  bool interrupted = false;           ///< a stop was requested through `interrupts`
  bool released = false;              ///< a second interrupt released the actuators at once
  RealtimeGrant realtime;             ///< what scheduling the loop got, and warnings
};

/// Ticks `controller` (which must have been begun at time 0, with a tick period of 1/rate_hz:
/// std::invalid_argument otherwise) while it is active: to the end of the show and the soft
/// stop, or through the fail-safe actions of a fault. `interrupts`
/// counts Ctrl-C / SIGTERM: the first asks for a soft stop to rest, the second releases at once.
RunResult run_loop(Controller& controller, const RunOptions& options, TickObserver& observer, const std::atomic<int>& interrupts);

}  // namespace avar::control
