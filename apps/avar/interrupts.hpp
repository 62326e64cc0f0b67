#pragma once
// Ctrl-C and SIGTERM as a counter the loop polls: the first asks for a soft stop, the second for
// an immediate release. Ctrl-\ (SIGQUIT) is the terminal's e-stop: a fault, with every actuator's
// fail-safe action. The handlers only touch atomics (async-signal-safe).

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

}  // namespace avar::app
