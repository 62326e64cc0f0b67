#pragma once
// The count of allocations allocation_counter.hpp's operator new keeps. Include this one in the
// other test files of a binary that read the count (allocation_counter.hpp itself only once).

#include <atomic>

namespace avar::testing {
inline std::atomic<long> allocations{0};
/// The same count, of the calling thread's allocations only (a simulated device serving on its
/// own thread does not count against the loop's).
inline thread_local long thread_allocations = 0;
}  // namespace avar::testing
