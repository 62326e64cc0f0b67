// A CAN bus of drives: `can: {bitrate, interface, reply_timeout_ms, heartbeat_ms,
// heartbeat_timeout_ms, mit_master_id}`; each actuator names its drive protocol and node.
#include <cstdio>
#include <numbers>

#include "avar/core/format.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

constexpr const char* kBitrates = "10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000, 1000000";

/// "an ODrive", "a CiA 402 drive".
std::string with_article(const char* name) {
  const char c = name[0];
  return std::string(c == 'A' || c == 'E' || c == 'I' || c == 'O' || c == 'U' || c == 'M' ? "an " : "a ") + name;
}

bool is_device_path(const std::string& port) { return port.rfind("/dev/", 0) == 0; }

LinkOptions parse_can(const LinkSpec& link, const LinkSettings& s) {
  s.expect_only_keys({"bitrate", "interface", "reply_timeout_ms", "heartbeat_ms", "heartbeat_timeout_ms", "mit_master_id"});
  CanOptions o;
  if (const ScalarValue* m = s.find("mit_master_id"))
    o.mit_master_id = static_cast<std::uint32_t>(integer_in(*m, "mit_master_id", 0, firmware_iface::kCanMaxStandardId));
  if (const ScalarValue* b = s.find("bitrate")) {
    const long long bitrate = b->as_integer("bitrate");
    if (bitrate < 0 || bitrate > 1'000'000 || !firmware_iface::is_standard_can_bitrate(static_cast<int>(bitrate)))
      b->fail("expected a CAN bitrate in bit/s, one of: " + std::string(kBitrates) + "; found " + b->describe());
    o.bitrate = static_cast<int>(bitrate);
  }
  if (const ScalarValue* i = s.find("interface")) {
    const std::string kind = i->as_string("interface");
    if (kind != "slcan" && kind != "socketcan")
      i->fail(
          "unknown CAN interface " + i->describe() +
          "; expected slcan (a serial adapter such as a CANable or USBtin) or socketcan (a Linux CAN interface such as can0)");
    if (!link.simulated() && kind == "socketcan" && is_device_path(link.port))
      i->fail("a SocketCAN interface is named like can0, not a device path; for the adapter on " + link.port +
              " write interface: slcan");
    o.interface = kind == "slcan" ? CanInterface::slcan : CanInterface::socketcan;
  }
  if (const ScalarValue* t = s.find("reply_timeout_ms"))
    o.reply_timeout_ms = static_cast<int>(integer_in(*t, "reply_timeout_ms", 1, 1000, "ms"));
  if (const ScalarValue* h = s.find("heartbeat_ms"))
    o.heartbeat_ms = static_cast<int>(integer_in(*h, "heartbeat_ms", 10, 10000, "ms"));
  if (const ScalarValue* t = s.find("heartbeat_timeout_ms"))
    o.heartbeat_timeout_ms =
        static_cast<int>(integer_in(*t, "heartbeat_timeout_ms (longer than heartbeat_ms " + std::to_string(o.heartbeat_ms) + ")",
                                    o.heartbeat_ms + 1, 60000, "ms"));
  return o;
}

/// Channel units per output-shaft turn from the channel's unit, when it says.
std::optional<double> units_per_turn_of(const std::string& unit) {
  if (unit == "deg" || unit == "degree" || unit == "degrees" || unit == "°") return 360.0;
  if (unit == "rad" || unit == "radian" || unit == "radians") return 2 * std::numbers::pi;
  if (unit == "turn" || unit == "turns" || unit == "rev" || unit == "revolutions") return 1.0;
  return std::nullopt;
}

constexpr std::string_view kCommonDriveKeys[] = {"protocol", "node", "gear_ratio", "units_per_turn", "zero", "reverse"};

void finish_can_actuator(const Rig& rig, ActuatorSpec& a, const LinkSettings& s) {
  const ChannelSpec& ch = rig.channel(a.channel);
  const ScalarValue* protocol = s.find("protocol");
  if (!protocol)
    ScalarValue{"", false, "nothing", a.where}.fail("expected the drive protocol of an actuator on CAN link '" +
                                                    rig.link(a.link).name + "': protocol: " + drive_names());
  const CanDriveSchema* drive = find_drive_schema(protocol->as_string("protocol"));
  if (!drive) protocol->fail("unknown CAN drive protocol " + protocol->describe() + "; expected one of: " + drive_names());
  a.drive = drive->name;
  std::vector<std::string_view> keys(std::begin(kCommonDriveKeys), std::end(kCommonDriveKeys));
  for (std::string_view k : drive->keys()) keys.push_back(k);
  s.expect_only_keys(keys);
  if (const ScalarValue* n = s.find("node"))
    integer_in(*n, "the node id of " + with_article(drive->device_name), drive->node_low, drive->node_high);

  const double gear =
      s.find("gear_ratio") ? number_in(*s.find("gear_ratio"), "gear_ratio (motor turns per output turn)", 1e-3, 1e4) : 1.0;
  double per_turn = 0;
  if (const ScalarValue* u = s.find("units_per_turn")) {
    per_turn = number_in(*u, "units_per_turn (" + ch.unit + " per output turn)", 1e-9, 1e9);
  } else {
    const std::optional<double> known = units_per_turn_of(ch.unit);
    if (!known)
      ScalarValue{"", false, "nothing", a.where}.fail(
          "channel '" + ch.name + "' is in '" + ch.unit +
          "', which does not say how far one output turn goes: give units_per_turn (" + ch.unit +
          " per output turn; deg, rad and turn channels need none)");
    per_turn = *known;
  }
  const double zero = s.find("zero") ? s.find("zero")->as_double("zero (the channel value at the motor's zero)") : 0.0;
  const bool reverse = s.find("reverse") && s.find("reverse")->as_bool("reverse");
  a.options = drive->parse(s, a.device_channel, a.where);
  const double device_per_unit = (reverse ? -1.0 : 1.0) * gear * drive->device_units_per_turn(a) / per_turn;
  a.calibration = {};
  a.calibration.channel_min = ch.min;
  a.calibration.channel_max = ch.max;
  a.calibration.device_at_min = (ch.min - zero) * device_per_unit;
  a.calibration.device_at_max = (ch.max - zero) * device_per_unit;
  drive->validate(a);
}

std::string hex_id(std::uint32_t id) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%03X", id);
  return text;
}

void validate_can_actuators(const Rig& rig, std::size_t link) {
  const LinkSpec& spec = rig.links[link];
  const CanOptions& bus = spec.options_as<CanOptions>();
  struct Use {
    const ActuatorSpec* actuator;
    CanIdRange range;
  };
  std::vector<Use> uses;
  std::vector<CanIdRange> ranges;
  for (const ActuatorSpec& a : rig.actuators_on(LinkIndex{link})) {
    const CanDriveSchema& drive = drive_schema_of(a);
    const auto fail_at_node = [&a](const std::string& problem) { throw InputError(a.address_where, problem); };
    if (!drive.accepts_bitrate(bus.bitrate))
      fail_at_node(with_article(drive.device_name) + " cannot run at the " + std::to_string(bus.bitrate) + " bit/s of link '" +
                   spec.name + "'; expected one of: " + drive.bitrates_text);
    ranges.clear();
    drive.can_ids(a, bus, ranges);
    for (const CanIdRange& r : ranges) {
      for (const Use& u : uses) {
        const bool overlap = r.first <= u.range.last && u.range.first <= r.last;
        if (!overlap || (r.shared && u.range.shared && u.actuator->drive == a.drive)) continue;
        const std::uint32_t id = std::max(r.first, u.range.first);
        fail_at_node(std::string(drive.device_name) + " node " + std::to_string(a.device_channel) + " uses CAN id " + hex_id(id) +
                     ", which the " + drive_schema_of(*u.actuator).device_name + " at node " +
                     std::to_string(u.actuator->device_channel) + " (line " + std::to_string(u.actuator->where.line) +
                     ") also uses on link '" + spec.name + "'; expected a node whose identifiers are free");
      }
      uses.push_back({&a, r});
    }
  }
}

}  // namespace

const ProtocolSchema& can_schema() {
  static const ProtocolSchema p{
      .name = "can",
      .device_name = "CAN bus",
      .default_baud = 115200,
      .bauds_text = "any standard serial rate (USB adapters such as the CANable ignore it)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_can,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"node", 0, firmware_iface::kCanMaxStandardId, nullptr, nullptr, nullptr, 0, 0, ""};
      },
      .reports_telemetry = [](const LinkSpec&) { return true; },
      .finish_actuator = finish_can_actuator,
      .validate_link_actuators = validate_can_actuators,
  };
  return p;
}

}  // namespace avar::rig
