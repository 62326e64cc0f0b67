#include "avar/firmware_iface/maestro_actuators.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::firmware_iface {

void check_maestro_channels(std::span<const MaestroActuator> actuators, int channel_count) {
  std::vector<bool> used(static_cast<std::size_t>(channel_count), false);
  for (const MaestroActuator& a : actuators) {
    if (a.device_channel < 0 || a.device_channel >= channel_count)
      throw std::invalid_argument("Maestro channel " + std::to_string(a.device_channel) + " is outside 0.." +
                                  std::to_string(channel_count - 1));
    if (used[static_cast<std::size_t>(a.device_channel)])
      throw std::invalid_argument("Maestro channel " + std::to_string(a.device_channel) + " is used twice");
    used[static_cast<std::size_t>(a.device_channel)] = true;
  }
}

// 0 means "no limit" to the Maestro, which is also what an absent limit means here.
std::uint16_t maestro_speed_units(const MaestroActuator& a) noexcept {
  return a.speed_us_per_s ? maestro::speed_units_from_us_per_s(*a.speed_us_per_s) : 0;
}

std::uint16_t maestro_acceleration_units(const MaestroActuator& a) noexcept {
  return a.acceleration_us_per_s2 ? maestro::acceleration_units_from_us_per_s2(*a.acceleration_us_per_s2) : 0;
}

std::uint16_t maestro_target(ActuatorTable& table, std::size_t i, std::span<const double> frame) noexcept {
  // Target 0 stops the pulses of a released actuator.
  return table.released(i) ? std::uint16_t{0} : maestro::quarter_us_from_us(table.to_device(i, frame));
}

}  // namespace avar::firmware_iface
