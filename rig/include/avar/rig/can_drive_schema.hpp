#pragma once
// The schema of every drive protocol on a CAN link (ODrive, CiA 402, MIT-style): an actuator's
// own keys and how they parse into typed options, the node range, and the identifiers a drive
// uses on the bus. Pure data and parsing. A new drive protocol adds one schema
// (rig/src/schema/) and one line in drive_schemas(); its driver and simulated drive join the
// assembly's CAN drive registry. Load-time only.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "avar/rig/link_options.hpp"
#include "avar/rig/rig.hpp"

namespace avar::rig {

/// Identifiers a drive uses on the bus, both directions, inclusive.
struct CanIdRange {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  /// Every drive of the protocol uses it alike (MIT replies to the master id, CANopen NMT and
  /// SYNC): no conflict between drives of the same protocol.
  bool shared = false;
};

struct CanDriveSchema {
  const char* name;         ///< as actuators write it: `protocol: odrive`
  const char* device_name;  ///< for messages: "ODrive"
  long long node_low, node_high;
  const char* device_unit;  ///< the drive's position unit: "turns", "counts", "rad"
  const char* bitrates_text;
  bool (*accepts_bitrate)(int bitrate);
  /// Keys of its own an actuator may have beyond the common drive keys.
  std::span<const std::string_view> (*keys)();
  /// Parses those keys' values (the key set is already checked; `own` holds them) into options;
  /// throws InputError at the key (or at the actuator, `where`, for a missing one).
  ActuatorOptions (*parse)(const LinkSettings& own, int node, const SourceLocation& where);
  /// The drive's position unit per motor turn (ODrive 1, MIT 2π, CiA 402 its counts per turn).
  double (*device_units_per_turn)(const ActuatorSpec& a);
  /// Checks the actuator once its calibration is known (the drive's position range).
  void (*validate)(const ActuatorSpec& a);
  /// Appends the identifiers the drive of actuator `a` sends or listens on.
  void (*can_ids)(const ActuatorSpec& a, const CanOptions& bus, std::vector<CanIdRange>& out);
};

std::span<const CanDriveSchema* const> drive_schemas();
const CanDriveSchema* find_drive_schema(std::string_view name);
/// The drive schema of an actuator of a parsed rig (std::invalid_argument when unknown).
const CanDriveSchema& drive_schema_of(const ActuatorSpec& a);
/// "odrive, cia402, mit" for messages.
std::string drive_names();

}  // namespace avar::rig
