#pragma once
// The count of allocations allocation_counter.hpp's operator new keeps. Include this one in the
// other test files of a binary that read the count (allocation_counter.hpp itself only once).

#include <atomic>

namespace avar::testing {
inline std::atomic<long> allocations{0};
}
