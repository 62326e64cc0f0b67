#pragma once
// InputCounters kept by an input device's thread and read from any thread: one relaxed atomic per
// counter (each value is exact; a snapshot is not one instant across counters). And the arrival
// clock every input source stamps its messages with.

#include <time.h>

#include <atomic>
#include <cstdint>

#include "avar/inputs/input_source.hpp"

namespace avar::inputs {

struct AtomicInputCounters {
  std::atomic<std::uint64_t> messages{0};
  std::atomic<std::uint64_t> ignored{0};

  /// Counts one message taken, and whether it was ignored. Real-time safe.
  void count(bool was_ignored) noexcept {
    messages.fetch_add(1, std::memory_order_relaxed);
    if (was_ignored) ignored.fetch_add(1, std::memory_order_relaxed);
  }

  /// Adds a batch. Real-time safe.
  void add(const InputCounters& c) noexcept {
    messages.fetch_add(c.messages, std::memory_order_relaxed);
    ignored.fetch_add(c.ignored, std::memory_order_relaxed);
  }

  /// Real-time safe; any thread.
  InputCounters snapshot() const noexcept {
    return {messages.load(std::memory_order_relaxed), ignored.load(std::memory_order_relaxed)};
  }
};

/// CLOCK_MONOTONIC now, in nanoseconds: the `arrived_ns` of ControlSink::post. Real-time safe.
inline std::int64_t input_arrival_now_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace avar::inputs
