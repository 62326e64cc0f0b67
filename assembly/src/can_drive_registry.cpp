#include <cmath>
#include <stdexcept>

#include "avar/assembly/can_drive.hpp"
#include "can_drives/can_drive_entries.hpp"
#include "avar/firmware_iface/can_frame.hpp"

namespace avar::assembly {

const std::vector<const CanDriveProtocol*>& can_drive_protocols() {
  static const std::vector<const CanDriveProtocol*> all{&odrive_drive(), &cia402_drive(), &mit_drive()};
  return all;
}

const CanDriveProtocol* find_can_drive(std::string_view name) {
  for (const CanDriveProtocol* d : can_drive_protocols())
    if (name == d->name) return d;
  return nullptr;
}

const CanDriveProtocol& can_drive_of(const rig::ActuatorSpec& a) {
  if (const CanDriveProtocol* d = find_can_drive(a.drive)) return *d;
  throw std::invalid_argument("unknown CAN drive protocol '" + a.drive + "'");
}

const rig::CanDriveSchema& schema_of(const CanDriveProtocol& d) {
  if (const rig::CanDriveSchema* schema = rig::find_drive_schema(d.name)) return *schema;
  throw std::invalid_argument(std::string("CAN drive protocol '") + d.name + "' has no schema");
}

}  // namespace avar::assembly
