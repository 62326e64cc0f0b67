#include "avar/assembly/servo_bus_options.hpp"

#include "avar/firmware_iface/device_watch.hpp"

namespace avar::assembly {

std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link) {
  return firmware_iface::silence_budget(rig.links[link].watchdog_s, rig.rate_hz);
}

}  // namespace avar::assembly
