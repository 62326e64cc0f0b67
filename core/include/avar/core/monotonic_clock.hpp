#pragma once
// The host's monotonic clock: what the runner paces real time on, what live inputs and timecode
// sources stamp arrivals with, what the controller times its stages on. Code below the runner
// that must not read a clock takes time as an argument instead (stepped sources, drivers).

#include <time.h>

#include <cstdint>

namespace avar {

/// CLOCK_MONOTONIC now, in nanoseconds. Any thread; real-time safe (no allocation, no lock).
inline std::int64_t monotonic_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace avar
