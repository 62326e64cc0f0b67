#include <algorithm>
#include <array>
#include <stdexcept>

#include "avar/core/serial_rates.hpp"
#include "schema_entries.hpp"

namespace avar::rig {

std::span<const ProtocolSchema* const> schemas() {
  static const std::array<const ProtocolSchema*, 12> all{
      &maestro_schema(), &dynamixel_schema(), &feetech_schema(), &ssc32_schema(),   &dmx_schema(),         &can_schema(),
      &gpio_schema(),    &artnet_schema(),    &sacn_schema(),    &pca9685_schema(), &avar_device_schema(), &pwm_schema()};
  return all;
}

const ProtocolSchema* find_schema(std::string_view name) {
  for (const ProtocolSchema* p : schemas())
    if (name == p->name) return p;
  return nullptr;
}

const ProtocolSchema& schema_of(const LinkSpec& link) {
  if (const ProtocolSchema* p = find_schema(link.protocol)) return *p;
  throw std::invalid_argument("link '" + link.name + "' speaks an unknown protocol '" + link.protocol + "'");
}

std::string protocol_names() {
  std::string names;
  for (const ProtocolSchema* p : schemas()) names += (names.empty() ? "" : ", ") + std::string(p->name);
  return names;
}

int checked_baud(const ProtocolSchema& p, const ScalarValue& written, std::string_view what) {
  const long long b = written.as_integer(what);
  if (!is_standard_baud(b))
    written.fail("expected a standard serial baud rate (9600, 19200, 38400, 57600, 115200, 230400, 1000000...), found " +
                 written.describe());
  if (!p.device_accepts_baud(static_cast<int>(b)))
    written.fail("a " + std::string(p.name) + " device cannot run at " + written.describe() +
                 " baud; expected one of: " + p.bauds_text);
  return static_cast<int>(b);
}

std::size_t index_on_link(const Rig& rig, const ActuatorSpec& wanted) {
  std::size_t i = 0;
  for (const ActuatorSpec& a : rig.actuators_on(wanted.link)) {
    if (&a == &wanted) return i;
    ++i;
  }
  return i;
}

std::span<const CanDriveSchema* const> drive_schemas() {
  static const std::array<const CanDriveSchema*, 3> all{&odrive_schema(), &cia402_schema(), &mit_schema()};
  return all;
}

const CanDriveSchema* find_drive_schema(std::string_view name) {
  for (const CanDriveSchema* d : drive_schemas())
    if (name == d->name) return d;
  return nullptr;
}

const CanDriveSchema& drive_schema_of(const ActuatorSpec& a) {
  if (const CanDriveSchema* d = find_drive_schema(a.drive)) return *d;
  throw std::invalid_argument("unknown CAN drive protocol '" + a.drive + "'");
}

std::string drive_names() {
  std::string names;
  for (const CanDriveSchema* d : drive_schemas()) names += (names.empty() ? "" : ", ") + std::string(d->name);
  return names;
}

}  // namespace avar::rig
