#pragma once
// Real-time scheduling for the loop thread: SCHED_FIFO at a chosen priority, memory locked
// against paging, and pinning to one CPU, each when the system permits it. What is refused is
// reported as a warning and the loop runs on without it. Call once before the loop starts (not
// real-time itself: it may allocate the warnings).

#include <string>
#include <vector>

namespace avar::control {

struct RealtimeRequest {
  int priority = 0;         ///< SCHED_FIFO priority 1..99; 0 = keep the normal scheduler
  bool lock_memory = false; ///< mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;             ///< pin the calling thread to this CPU; -1 = anywhere
};

struct RealtimeGrant {
  bool fifo = false;
  bool memory_locked = false;
  bool pinned = false;
  std::vector<std::string> warnings;  ///< one line each, saying what was refused and what to do
};

/// Applies the request to the calling thread (and, for memory, the process).
RealtimeGrant apply_realtime(const RealtimeRequest& request);

/// Puts the calling thread back on the normal scheduler (SCHED_OTHER), on every CPU, and
/// unlocks memory.
void release_realtime(const RealtimeGrant& grant);

}  // namespace avar::control
