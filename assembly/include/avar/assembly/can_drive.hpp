#pragma once
// The registry of CAN drive protocols: how avar makes the drives of one kind on a CAN link
// (ODrive, CiA 402, MIT-style) and simulates one, in one entry. What an actuator's drive keys are
// and how they parse is the drive's schema in the rig (avar/rig/can_drive_schema.hpp). A new drive
// protocol joins by a schema, one entry (its own file under assembly/src/can_drives/) and one line
// in the list of can_drive_protocols(). The `can` link protocol (assembly/src/protocols/can.cpp)
// reaches every drive through here. Load-time only.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "avar/firmware_iface/can_drives.hpp"
#include "avar/assembly/sim_offer.hpp"
#include "avar/rig/can_drive_schema.hpp"
#include "avar/rig/rig.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::assembly {

/// The `can` settings of a link that every drive set needs.
struct CanBusOptions {
  int bitrate = 1'000'000;          ///< bit/s
  int reply_timeout_ms = 5;         ///< longest a tick waits for the drives' replies
  int heartbeat_ms = 100;           ///< heartbeat period the drives produce (where configurable)
  std::uint32_t silent_ticks = 30;  ///< ticks in a row without a heartbeat or reply that make a drive lost
  std::uint32_t mit_master_id = 0;  ///< the id MIT-style motors reply to (their CAN_MASTER)
};

/// A simulated drive for one actuator and its true position in the drive's own unit.
struct SimulatedDrive {
  std::unique_ptr<sim::CanNode> node;
  std::function<double()> device_position;
};

struct CanDriveProtocol {
  const char* name;  ///< its schema's name (rig::find_drive_schema): `odrive`
  /// The drive set for these actuators (all of this protocol, on one link of a validated rig).
  std::unique_ptr<firmware_iface::CanDrives> (*make_drives)(const rig::Rig& rig,
                                                            std::span<const rig::ActuatorSpec* const> actuators,
                                                            const CanBusOptions& bus);
  /// A simulated drive at `node`, its position `position` (the drive's unit), set up as the
  /// owner of actuator `a` would have set up the real one (null: factory settings, for
  /// `avar sim slcan`).
  SimulatedDrive (*make_simulated)(const rig::ActuatorSpec* a, std::uint32_t node, double position, const CanBusOptions& bus);
  /// What `avar sim NAME` serves: drives of this protocol behind a simulated SLCAN adapter.
  SimOffer sim;
};

const std::vector<const CanDriveProtocol*>& can_drive_protocols();
const CanDriveProtocol* find_can_drive(std::string_view name);
/// The drive protocol of an actuator of a validated rig (std::invalid_argument when unknown).
const CanDriveProtocol& can_drive_of(const rig::ActuatorSpec& a);
/// Its schema.
const rig::CanDriveSchema& schema_of(const CanDriveProtocol& d);

/// What the drive sets of link `link` of a parsed rig need: its `can` options with the silence
/// budget in ticks at the rig's rate.
CanBusOptions can_bus_options(const rig::Rig& rig, std::size_t link);

}  // namespace avar::assembly
