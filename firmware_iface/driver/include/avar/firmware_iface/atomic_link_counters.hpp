#pragma once
// LinkCounters kept by a driver's sending thread and read from any thread
// (avar/core/atomic_counters.hpp): counters_.add(&LinkCounters::timeouts), counters_.snapshot().

#include "avar/core/atomic_counters.hpp"
#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::firmware_iface {

using AtomicLinkCounters = AtomicCounters<LinkCounters>;

}  // namespace avar::firmware_iface
