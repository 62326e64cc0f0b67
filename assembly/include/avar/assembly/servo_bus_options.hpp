#pragma once
// What the polled smart-servo buses (DYNAMIXEL, Feetech) and the Maestro on USB take from the rig
// beyond their parsed options (avar::rig::ServoBusOptions): the silence budget.

#include <cstdint>

#include "avar/rig/rig.hpp"

namespace avar::assembly {

/// The silence budget of a link's devices, in exchanges: the link's watchdog time at the rig's
/// tick rate (firmware_iface::silence_budget, device_watch.hpp).
std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link);

}  // namespace avar::assembly
