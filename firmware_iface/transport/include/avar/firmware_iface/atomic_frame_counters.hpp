#pragma once
// FrameCounters kept by a frame transport's I/O thread and read from any thread: one relaxed
// atomic per counter (each value is exact; a snapshot is not one instant across counters).

#include <atomic>
#include <cstdint>

#include "avar/firmware_iface/frame_transport.hpp"

namespace avar::firmware_iface {

struct AtomicFrameCounters {
  std::atomic<std::uint64_t> frames_sent{0};
  std::atomic<std::uint64_t> frames_received{0};
  std::atomic<std::uint64_t> error_frames{0};
  std::atomic<std::uint64_t> bus_off{0};
  std::atomic<std::uint64_t> bytes_sent{0};
  std::atomic<std::uint64_t> bytes_received{0};
  std::atomic<std::uint64_t> malformed{0};

  /// Adds n to one counter. Real-time safe.
  static void add(std::atomic<std::uint64_t>& counter, std::uint64_t n = 1) noexcept {
    counter.fetch_add(n, std::memory_order_relaxed);
  }

  /// Counts one received frame: data and remote frames, or an error frame (and a bus-off).
  void count_received(const CanFrame& f) noexcept {
    if (!f.error) {
      add(frames_received);
      return;
    }
    add(error_frames);
    if (f.id & kCanErrorBusOff) add(bus_off);
  }

  /// Real-time safe; any thread.
  FrameCounters snapshot() const noexcept {
    const auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
    return {get(frames_sent), get(frames_received), get(error_frames), get(bus_off),
            get(bytes_sent),  get(bytes_received),  get(malformed)};
  }
};

}  // namespace avar::firmware_iface
