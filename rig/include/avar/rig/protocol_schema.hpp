#pragma once
// The schema of every protocol a link may speak: its settings block's name, what it accepts, and
// how its settings and its actuators' own keys parse into typed options (link_options.hpp). Pure
// data and parsing: no driver, transport or simulator. The rig readers (avar::config) use it; the
// assembly (avar::assembly) turns the parsed options into drivers and simulated devices. A new
// protocol adds one schema (rig/src/schema/) and one line in schemas(). Load-time only; every
// failure is an InputError naming the file, line, what was found and what was expected.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "avar/core/scalar_value.hpp"
#include "avar/rig/link_options.hpp"
#include "avar/rig/rig.hpp"

namespace avar::rig {

/// How an actuator is addressed and calibrated on a link.
struct AddressRule {
  const char* key;      ///< device_channel, id, address, node or line
  long long low, high;  ///< valid addresses
  const char* cal_min;  ///< calibration keys; nullptr: the actuator takes no calibration block
  const char* cal_max;
  const char* trim;
  double device_low, device_high;  ///< the device's own range
  const char* unit;
};

struct ProtocolSchema {
  const char* name;         ///< the settings block's key in a rig file: `maestro: {...}`
  const char* device_name;  ///< for messages: "Maestro"
  int default_baud;
  const char* bauds_text;  ///< the rates the device runs at, for messages
  bool (*device_accepts_baud)(int baud);
  /// The link's settings block (`settings`), checked whole (keys, types, ranges) and parsed;
  /// `link` has its name, port and baud. Throws InputError at the setting.
  LinkOptions (*parse)(const LinkSpec& link, const LinkSettings& settings);
  /// Whether the link may leave out its port because the device is found otherwise (a Maestro
  /// on USB by its serial number, a node on the network); its port is then "". Asked of the
  /// settings as written, before parse. nullptr: the port is required.
  bool (*port_optional)(const LinkSettings& settings) = nullptr;
  /// Addresses on a link of a parsed rig (`fine`: a 16-bit DMX actuator).
  AddressRule (*address_rule)(const LinkSpec& link, bool fine) = nullptr;
  /// Whether the actuator may set `fine` (16-bit DMX).
  bool has_fine_addresses = false;
  /// Whether an actuator must be calibrated (a DMX dimmer spans its range by default).
  bool needs_calibration = false;
  /// Whether the devices report telemetry (position, load, temperature) with these settings.
  bool (*reports_telemetry)(const LinkSpec& link) = nullptr;

  /// Keys an actuator on this protocol's links takes besides the common ones and its address key
  /// (gpio: active_low). Not for buses of drives.
  std::vector<std::string_view> actuator_keys = {};
  /// Parses and checks one actuator once read (its channel's kind, its own keys, `own`: those
  /// of actuator_keys it has) into a.options; throws InputError at the key. nullptr: nothing more.
  void (*check_actuator)(const Rig& rig, ActuatorSpec& a, const LinkSettings& own) = nullptr;

  // Buses of drives (CAN) only; nullptr for every other protocol.

  /// Parses an actuator's own keys (`own`: everything but channel, link, speed, acceleration
  /// and failsafe), fills a.drive, a.options and a.calibration. Throws InputError at the key. A
  /// protocol with this hook takes no calibration block.
  void (*finish_actuator)(const Rig& rig, ActuatorSpec& a, const LinkSettings& own) = nullptr;
  /// Checks a link's actuators together once all are read (identifiers that collide on the bus,
  /// a bitrate a drive cannot run at). Replaces the one-address-one-actuator check. Throws
  /// InputError at the offending actuator.
  void (*validate_link_actuators)(const Rig& rig, std::size_t link) = nullptr;
};

/// Every protocol avar speaks, in the order messages list them.
std::span<const ProtocolSchema* const> schemas();
/// The schema called `name`, or nullptr.
const ProtocolSchema* find_schema(std::string_view name);
/// The schema of a link of a parsed rig (std::invalid_argument when unknown).
const ProtocolSchema& schema_of(const LinkSpec& link);
/// "maestro, dynamixel, ..." for messages.
std::string protocol_names();

/// The baud rate written for a link of protocol `p` (`what` names it: "the baud rate of link
/// 'arm'"): a standard serial rate that the device runs at. Throws InputError at the value.
int checked_baud(const ProtocolSchema& p, const ScalarValue& written, std::string_view what);

/// Index of an actuator among its link's actuators (the order drivers and simulated devices
/// list them in).
std::size_t index_on_link(const Rig& rig, const ActuatorSpec& wanted);

}  // namespace avar::rig
