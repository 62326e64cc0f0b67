#include "avar/inputs/timecode_source.hpp"

namespace avar::inputs {

void TimecodeMailbox::publish(const TimecodeFix& fix, std::int64_t arrival_ns) noexcept {
  const std::uint64_t v = version_.load(std::memory_order_relaxed);
  version_.store(v + 1, std::memory_order_relaxed);
  // Seqlock without fences (ThreadSanitizer does not model them): each field's release store
  // orders the odd version before it, so a reader that sees a new field also sees the version move.
  seconds_.store(fix.seconds(), std::memory_order_release);
  arrival_ns_.store(arrival_ns, std::memory_order_release);
  rate_.store(static_cast<std::uint8_t>(fix.label.rate), std::memory_order_release);
  reverse_.store(fix.reverse, std::memory_order_release);
  version_.store(v + 2, std::memory_order_release);
}

TimecodeReading TimecodeMailbox::read() const noexcept {
  for (;;) {
    const std::uint64_t before = version_.load(std::memory_order_acquire);
    if (before & 1U) continue;
    TimecodeReading r;
    // Acquire loads keep the version's second read after them.
    r.seconds = seconds_.load(std::memory_order_acquire);
    r.arrival_ns = arrival_ns_.load(std::memory_order_acquire);
    r.rate = static_cast<FrameRate>(rate_.load(std::memory_order_acquire));
    r.reverse = reverse_.load(std::memory_order_acquire);
    if (version_.load(std::memory_order_relaxed) != before) continue;
    r.sequence = before / 2;
    return r;
  }
}

}  // namespace avar::inputs
