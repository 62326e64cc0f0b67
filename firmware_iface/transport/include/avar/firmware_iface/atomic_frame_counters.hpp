#pragma once
// FrameCounters kept by a frame transport's I/O thread and read from any thread
// (avar/core/atomic_counters.hpp).

#include "avar/core/atomic_counters.hpp"
#include "avar/firmware_iface/frame_transport.hpp"

namespace avar::firmware_iface {

using AtomicFrameCounters = AtomicCounters<FrameCounters>;

/// Counts one received frame: data and remote frames, or an error frame (and a bus-off).
/// Real-time safe.
inline void count_received(AtomicFrameCounters& counters, const CanFrame& f) noexcept {
  if (!f.error) {
    counters.add(&FrameCounters::frames_received);
    return;
  }
  counters.add(&FrameCounters::error_frames);
  if (f.id & kCanErrorBusOff) counters.add(&FrameCounters::bus_off);
}

}  // namespace avar::firmware_iface
