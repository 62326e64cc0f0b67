#pragma once
// The one policy for a device that falls silent, kept by every driver that expects answers: each
// servo of a polled serial bus (BusExchange), a Maestro on USB (MaestroUsbLink), and each drive of
// a CAN drive set (ODrive and CiA 402 heartbeats, MIT motor replies).
//
// Silence is counted in ticks (one exchange or one settle() each), never on a clock: a simulated
// device's time and the host's clock may run at different speeds, ticks never do.
//
// - The budget. A watchdog time W (a link's `watchdog_ms`; a CAN drive's `heartbeat_timeout_ms`)
//   at a tick period T is silence_budget(W, 1/T) = max(2, ceil(W / T)) ticks: the fewest whole
//   ticks that last at least W (the rounding error of the division is ignored: 70 ms at 100 Hz is
//   7 ticks, not 8), and never fewer than 2, so that one lost reply alone is never a fault.
// - A silent tick is a tick in which the device was expected to answer (asked, or due to beat
//   its heart) and no answer was taken. Ticks in which nothing was expected of the device (not
//   asked, released) neither count nor reset.
// - The fault. The device is lost from the tick whose silent ticks in a row reach the budget
//   (silent_ticks() >= budget()): silence of W, in ticks. For a reply asked every tick that is
//   W (rounded up to a tick) after the last answer; for a heartbeat taken at the next settle()
//   after it arrived, at least W and less than W + 2 T after it. Never earlier than W.
// - A budget of 0 is taken as 1: the first silent tick is the fault.
// - What resets it: an answer taken in a tick (a well-formed reply, a heartbeat) empties the
//   count at once, and the device is no longer lost; a later silence gets the whole budget again.
//
// What a lost device costs is the driver's to say: on a polled serial bus and on the Maestro's USB
// link the exchange is shared, so send() returns timeout (the controller's link watchdog fault); a
// CAN drive set marks the drive's channel kDeviceLost (a channel fault), the bus and its other
// drives going on.
//
// Threads: one thread (the link's I/O thread, or the loop's). Real-time safe: no allocation, no
// exception, no clock.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace avar::firmware_iface {

/// The smallest budget silence_budget() derives: one lost reply alone is never a fault.
inline constexpr std::uint32_t kMinSilenceBudget = 2;

/// The budget, in ticks, of a watchdog time of `watchdog_s` seconds at `tick_hz` ticks per
/// second: max(kMinSilenceBudget, ceil(watchdog_s * tick_hz)), the product's rounding error
/// (below 1e-9 tick) ignored. A product that is not a number or not above the minimum gives
/// kMinSilenceBudget; one beyond the counter's range (infinity included) saturates.
inline std::uint32_t silence_budget(double watchdog_s, double tick_hz) noexcept {
  const double ticks = watchdog_s * tick_hz;
  if (std::isnan(ticks) || ticks <= kMinSilenceBudget) return kMinSilenceBudget;
  constexpr double kMax = std::numeric_limits<std::uint32_t>::max();
  return static_cast<std::uint32_t>(std::min(kMax, std::ceil(ticks - 1e-9)));
}

/// The silence of one device against its budget (see above).
class DeviceWatch {
 public:
  /// `budget_ticks`: silent ticks in a row that make the device lost (0 is taken as 1).
  explicit constexpr DeviceWatch(std::uint32_t budget_ticks = 1) noexcept : budget_(std::max<std::uint32_t>(1, budget_ticks)) {}

  /// An answer was taken this tick: the count starts again, the device is not lost.
  constexpr void answered() noexcept { silent_ = 0; }
  /// The device was expected to answer this tick and did not (saturating count). Returns lost().
  constexpr bool missed() noexcept {
    if (silent_ < std::numeric_limits<std::uint32_t>::max()) ++silent_;
    return lost();
  }
  /// silent_ticks() has reached the budget.
  constexpr bool lost() const noexcept { return silent_ >= budget_; }
  /// Silent ticks in a row so far.
  constexpr std::uint32_t silent_ticks() const noexcept { return silent_; }
  constexpr std::uint32_t budget() const noexcept { return budget_; }

 private:
  std::uint32_t budget_;
  std::uint32_t silent_ = 0;
};

}  // namespace avar::firmware_iface
