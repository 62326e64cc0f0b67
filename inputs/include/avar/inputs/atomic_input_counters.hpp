#pragma once
// InputCounters kept by an input device's thread and read from any thread
// (avar/core/atomic_counters.hpp). Input sources stamp their messages with avar::monotonic_ns()
// (avar/core/monotonic_clock.hpp).

#include "avar/core/atomic_counters.hpp"
#include "avar/inputs/input_source.hpp"

namespace avar::inputs {

using AtomicInputCounters = AtomicCounters<InputCounters>;

}  // namespace avar::inputs
