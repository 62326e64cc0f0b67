#include "avar/assembly/servo_bus_options.hpp"

#include <cmath>
#include <algorithm>

namespace avar::assembly {

std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link) {
  return std::max<std::uint32_t>(2, static_cast<std::uint32_t>(std::ceil(rig.links[link].watchdog_s * rig.rate_hz)));
}

}  // namespace avar::assembly
