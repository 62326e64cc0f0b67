#pragma once
// The registry of CAN drive protocols: everything avar knows about one kind of drive on a CAN
// link (ODrive, CiA 402, MIT-style), in one entry. A new drive protocol joins by one entry (its
// own file under assembly/src/can_drives/) and one line in the list of can_drive_protocols().
// The `can` link protocol (assembly/src/protocols/can.cpp) reaches every drive through here.
// Load-time only.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "avar/firmware_iface/can_drives.hpp"
#include "avar/rig/rig.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::assembly {

/// Identifiers a drive uses on the bus, both directions, inclusive.
struct CanIdRange {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  /// Every drive of the protocol uses it alike (MIT replies to the master id, CANopen NMT and
  /// SYNC): no conflict between drives of the same protocol.
  bool shared = false;
};

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
  const char* name;         ///< as actuators write it: `protocol: odrive`
  const char* device_name;  ///< for messages: "ODrive"
  long long node_low, node_high;
  const char* device_unit;  ///< the drive's position unit: "turns", "counts", "rad"
  const char* bitrates_text;
  bool (*accepts_bitrate)(int bitrate);
  /// Keys of its own an actuator may have beyond the common drive keys.
  std::span<const std::string_view> (*keys)();
  /// Checks those keys' values (the key set is already checked); throws InputError at the key.
  void (*validate)(const rig::ActuatorSpec& a);
  /// The drive's position unit per motor turn (ODrive 1, MIT 2π, CiA 402 its counts per turn).
  double (*device_units_per_turn)(const rig::ActuatorSpec& a);
  /// Appends the identifiers the drive of actuator `a` sends or listens on.
  void (*can_ids)(const rig::ActuatorSpec& a, const CanBusOptions& bus, std::vector<CanIdRange>& out);
  /// The drive set for these actuators (all of this protocol, on one link of a validated rig).
  std::unique_ptr<firmware_iface::CanDrives> (*make_drives)(const rig::Rig& rig,
                                                            std::span<const rig::ActuatorSpec* const> actuators,
                                                            const CanBusOptions& bus);
  /// A simulated drive at `node`, its position `position` (the drive's unit), set up as the
  /// owner of actuator `a` would have set up the real one (null: factory settings, for
  /// `avar sim slcan`).
  SimulatedDrive (*make_simulated)(const rig::ActuatorSpec* a, std::uint32_t node, double position, const CanBusOptions& bus);
};

const std::vector<const CanDriveProtocol*>& can_drive_protocols();
const CanDriveProtocol* find_can_drive(std::string_view name);
/// The drive protocol of an actuator of a validated rig (std::invalid_argument when unknown).
const CanDriveProtocol& can_drive_of(const rig::ActuatorSpec& a);
/// "odrive, cia402, mit" for messages.
std::string can_drive_names();

/// A link's `can` settings (validated at load).
CanBusOptions can_bus_options(const rig::Rig& rig, std::size_t link);

}  // namespace avar::assembly
