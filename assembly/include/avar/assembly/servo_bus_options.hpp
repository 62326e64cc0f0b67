#pragma once
// The settings every polled smart-servo bus shares (DYNAMIXEL, Feetech):
// `{readback, reply_timeout_ms, retries}`, and what a protocol adds to them.

#include <initializer_list>
#include <string_view>

#include "avar/rig/rig.hpp"

namespace avar::assembly {

/// What a smart-servo bus reads back every tick.
enum class Readback {
  none,      ///< write only
  position,  ///< present position
  full,      ///< position, load, temperature (and hardware errors on alert)
};

struct ServoBusOptions {
  Readback readback = Readback::full;
  int reply_timeout_ms = 10;  ///< longest wait for one exchange's replies
  int retries = 1;            ///< re-reads per exchange for lost replies
};

/// Reads the shared bus settings of a link whose block may also hold `extra_keys` (read by the
/// protocol itself). Throws InputError at the offending setting.
ServoBusOptions servo_bus_options(const rig::LinkSpec& link, std::initializer_list<std::string_view> extra_keys = {});

/// The silence budget of a link's devices, in exchanges: the link's watchdog time at the rig's
/// tick rate (firmware_iface::silence_budget, device_watch.hpp).
std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link);

}  // namespace avar::assembly
