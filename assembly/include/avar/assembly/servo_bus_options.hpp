#pragma once
// What the polled smart-servo buses (DYNAMIXEL, Feetech) and the Maestro on USB take from the rig
// beyond their parsed options (avar::rig::ServoBusOptions): the silence budget.

#include <cstdint>

#include "avar/rig/rig.hpp"

namespace avar::assembly {

/// How many exchanges a servo may miss before its silence is a fault: the link's watchdog time
/// at the rig's tick rate, at least 2.
std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link);

}  // namespace avar::assembly
