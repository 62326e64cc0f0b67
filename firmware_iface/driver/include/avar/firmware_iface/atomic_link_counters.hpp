#pragma once
// LinkCounters kept by a driver's sending thread and read from any thread: one relaxed atomic
// per counter (each value is exact; a snapshot is not one instant across counters).

#include <atomic>
#include <cstdint>

#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::firmware_iface {

struct AtomicLinkCounters {
  std::atomic<std::uint64_t> exchanges{0};
  std::atomic<std::uint64_t> bytes_sent{0};
  std::atomic<std::uint64_t> bytes_received{0};
  std::atomic<std::uint64_t> replies{0};
  std::atomic<std::uint64_t> crc_errors{0};
  std::atomic<std::uint64_t> framing_errors{0};
  std::atomic<std::uint64_t> timeouts{0};
  std::atomic<std::uint64_t> retries{0};
  std::atomic<std::uint64_t> device_errors{0};
  std::atomic<std::uint64_t> reconnects{0};

  /// Adds n to one counter. Real-time safe.
  static void add(std::atomic<std::uint64_t>& counter, std::uint64_t n = 1) noexcept {
    counter.fetch_add(n, std::memory_order_relaxed);
  }

  /// Real-time safe; any thread.
  LinkCounters snapshot() const noexcept {
    const auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
    return {get(exchanges), get(bytes_sent),    get(bytes_received), get(replies),       get(crc_errors),
            get(framing_errors), get(timeouts), get(retries),        get(device_errors), get(reconnects)};
  }
};

}  // namespace avar::firmware_iface
