#include "avar/control/runner.hpp"

#include <time.h>

#include <cerrno>
#include <cmath>
#include <stdexcept>

namespace avar::control {
namespace {

constexpr long kNanosPerSecond = 1'000'000'000L;

timespec add_ns(timespec t, long ns) {
  t.tv_nsec += ns;
  while (t.tv_nsec >= kNanosPerSecond) {
    t.tv_nsec -= kNanosPerSecond;
    ++t.tv_sec;
  }
  return t;
}

double seconds_between(const timespec& a, const timespec& b) {
  return static_cast<double>(b.tv_sec - a.tv_sec) + static_cast<double>(b.tv_nsec - a.tv_nsec) * 1e-9;
}

/// Sleeps until the absolute monotonic deadline, resuming after signals.
void sleep_until(const timespec& deadline) {
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

}  // namespace

RunResult run_loop(Controller& controller, const RunOptions& options, TickObserver& observer,
                   const std::atomic<int>& interrupts) {
  if (std::abs(1.0 / options.rate_hz - controller.tick_period()) > 1e-9 * controller.tick_period())
    throw std::invalid_argument("the run's rate does not match the controller's tick period");
  RunResult result;
  const bool realtime = options.clock == ClockMode::realtime;
  if (realtime) result.realtime = apply_realtime(options.realtime);
  const double dt = 1.0 / options.rate_hz;
  const long period_ns = static_cast<long>(static_cast<double>(kNanosPerSecond) / options.rate_hz + 0.5);
  timespec deadline{};
  clock_gettime(CLOCK_MONOTONIC, &deadline);
  int seen_interrupts = 0;
  double lateness = 0;

  for (std::uint64_t k = 0; controller.active(); ++k) {
    // Tick times are nominal (k * dt) in both modes, so a run's curve samples do not depend on
    // scheduling jitter; lateness is measured and reported instead.
    const double now = static_cast<double>(k) * dt;
    const int pending = interrupts.load(std::memory_order_relaxed);
    if (pending != seen_interrupts) {
      seen_interrupts = pending;
      result.interrupted = true;
      if (pending >= 2) {
        controller.release_now();
        result.released = true;
        break;
      }
      controller.request_stop(now);
    }
    const auto pressed = [](const std::atomic<bool>* e) { return e && e->load(std::memory_order_relaxed); };
    if (pressed(options.estop) || pressed(options.estop_input) || pressed(options.estop_remote))
      controller.fault(FaultCause::estop, 0, 0, now);
    if (result.deadline_misses > options.deadline_miss_budget)
      controller.fault(FaultCause::deadline_budget, 0, static_cast<double>(result.deadline_misses), now);

    observer.before_tick(k, now, controller);
    controller.tick(now);
    ++result.ticks;
    if (options.plant) options.plant->advance(dt);
    observer.after_tick(k, now, dt, lateness, controller);

    if (realtime) {
      deadline = add_ns(deadline, period_ns);
      timespec woke{};
      clock_gettime(CLOCK_MONOTONIC, &woke);
      if (seconds_between(deadline, woke) > 0) {
        // The work overran the next deadline: count it and re-anchor rather than bursting to
        // catch up (a burst would replay stale ticks back to back).
        ++result.deadline_misses;
        deadline = woke;
        lateness = 0;
        continue;
      }
      sleep_until(deadline);
      clock_gettime(CLOCK_MONOTONIC, &woke);
      lateness = seconds_between(deadline, woke);
      result.lateness.record(static_cast<std::int64_t>(lateness * 1e9));
    }
  }
  if (realtime) release_realtime(result.realtime);
  return result;
}

}  // namespace avar::control
