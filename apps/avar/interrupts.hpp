#pragma once
// Ctrl-C and SIGTERM as a counter the loop polls: the first asks for a soft stop, the second for
// an immediate release. Ctrl-\ (SIGQUIT) is the terminal's e-stop: a fault, with every actuator's
// fail-safe action. The handlers only touch atomics (async-signal-safe).

#include <csignal>

#include <atomic>

namespace avar::app {

/// Installs the SIGINT/SIGTERM/SIGQUIT handlers for the lifetime of the object and restores the previous
/// ones afterwards. One at a time per process.
class InterruptCounter {
 public:
  InterruptCounter();
  ~InterruptCounter();
  InterruptCounter(const InterruptCounter&) = delete;
  InterruptCounter& operator=(const InterruptCounter&) = delete;

  const std::atomic<int>& count() const noexcept;
  const std::atomic<bool>& estop() const noexcept;
};

/// SIGINT and SIGTERM blocked for the lifetime of the object (and so in threads started meanwhile,
/// which inherit the mask), to be taken synchronously: a serving loop waits on them instead of
/// sleeping. The previous mask comes back afterwards.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Waits up to `timeout_ms` (0: only looks) for SIGINT or SIGTERM; true when one came.
  bool wait(long timeout_ms) const;

 private:
  sigset_t stop_{};
  sigset_t previous_{};
};

}  // namespace avar::app
