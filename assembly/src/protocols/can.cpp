#include "avar/assembly/can_protocol.hpp"
#include "avar/assembly/simulated_can_bus.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "avar/assembly/can_drive.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/can_link.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/slcan_transport.hpp"
#include "avar/firmware_iface/socketcan_transport.hpp"
#include "../setting_reading.hpp"

namespace avar::assembly {
namespace {

constexpr const char* kBitrates = "10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000, 1000000";

/// "an ODrive", "a CiA 402 drive".
std::string with_article(const char* name) {
  const char c = name[0];
  return std::string(c == 'A' || c == 'E' || c == 'I' || c == 'O' || c == 'U' || c == 'M' ? "an " : "a ") + name;
}

bool is_device_path(const std::string& port) { return port.rfind("/dev/", 0) == 0; }

/// How a link reaches its bus: `interface` as written, else by the port's form.
bool uses_slcan(const rig::LinkSpec& link, const std::string& port) {
  if (const ScalarValue* i = link.settings.find("interface")) return i->text == "slcan";
  return is_device_path(port);
}

void validate_can_settings(const rig::LinkSpec& link) {
  const rig::LinkSettings& s = link.settings;
  s.expect_only_keys({"bitrate", "interface", "reply_timeout_ms", "heartbeat_ms", "heartbeat_timeout_ms", "mit_master_id"});
  if (const ScalarValue* m = s.find("mit_master_id")) integer_in(*m, "mit_master_id", 0, firmware_iface::kCanMaxStandardId);
  if (const ScalarValue* b = s.find("bitrate")) {
    const long long bitrate = b->as_integer("bitrate");
    if (bitrate < 0 || bitrate > 1'000'000 || !firmware_iface::is_standard_can_bitrate(static_cast<int>(bitrate)))
      b->fail("expected a CAN bitrate in bit/s, one of: " + std::string(kBitrates) + "; found " + b->describe());
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
  }
  if (const ScalarValue* t = s.find("reply_timeout_ms")) integer_in(*t, "reply_timeout_ms", 1, 1000, "ms");
  int heartbeat = 100;
  if (const ScalarValue* h = s.find("heartbeat_ms"))
    heartbeat = static_cast<int>(integer_in(*h, "heartbeat_ms", 10, 10000, "ms"));
  if (const ScalarValue* t = s.find("heartbeat_timeout_ms"))
    integer_in(*t, "heartbeat_timeout_ms (longer than heartbeat_ms " + std::to_string(heartbeat) + ")", heartbeat + 1, 60000,
               "ms");
}

/// Channel units per output-shaft turn from the channel's unit, when it says.
std::optional<double> units_per_turn_of(const std::string& unit) {
  if (unit == "deg" || unit == "degree" || unit == "degrees" || unit == "°") return 360.0;
  if (unit == "rad" || unit == "radian" || unit == "radians") return 2 * std::numbers::pi;
  if (unit == "turn" || unit == "turns" || unit == "rev" || unit == "revolutions") return 1.0;
  return std::nullopt;
}

constexpr std::string_view kCommonDriveKeys[] = {"protocol", "node", "gear_ratio", "units_per_turn", "zero", "reverse"};

void finish_can_actuator(const rig::Rig& rig, rig::ActuatorSpec& a) {
  const rig::LinkSettings& s = a.settings;
  const rig::ChannelSpec& ch = rig.channel(a.channel);
  const ScalarValue* protocol = s.find("protocol");
  if (!protocol)
    ScalarValue{"", false, "nothing", a.where}.fail("expected the drive protocol of an actuator on CAN link '" +
                                                    rig.link(a.link).name + "': protocol: " + can_drive_names());
  const CanDriveProtocol* drive = find_can_drive(protocol->as_string("protocol"));
  if (!drive) protocol->fail("unknown CAN drive protocol " + protocol->describe() + "; expected one of: " + can_drive_names());
  a.drive = drive->name;
  std::vector<std::string_view> keys(std::begin(kCommonDriveKeys), std::end(kCommonDriveKeys));
  for (std::string_view k : drive->keys()) keys.push_back(k);
  s.expect_only_keys(keys);
  if (const ScalarValue* n = s.find("node"))
    integer_in(*n, "the node id of " + with_article(drive->device_name), drive->node_low, drive->node_high);

  const double gear =
      s.find("gear_ratio") ? number_in(*s.find("gear_ratio"), "gear_ratio (motor turns per output turn)", 1e-3, 1e4) : 1.0;
  double per_turn = 0;
  if (const ScalarValue* u = s.find("units_per_turn"))
    per_turn = number_in(*u, "units_per_turn (" + ch.unit + " per output turn)", 1e-9, 1e9);
  else if (auto known = units_per_turn_of(ch.unit)) per_turn = *known;
  else
    ScalarValue{"", false, "nothing", a.where}.fail("channel '" + ch.name + "' is in '" + ch.unit +
                                                    "', which does not say how far one output turn goes: give units_per_turn (" +
                                                    ch.unit + " per output turn; deg, rad and turn channels need none)");
  const double zero = s.find("zero") ? s.find("zero")->as_double("zero (the channel value at the motor's zero)") : 0.0;
  const bool reverse = s.find("reverse") && s.find("reverse")->as_bool("reverse");
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

void validate_can_actuators(const rig::Rig& rig, std::size_t link) {
  const rig::LinkSpec& spec = rig.links[link];
  const CanBusOptions bus = can_bus_options(rig, link);
  struct Use {
    const rig::ActuatorSpec* actuator;
    CanIdRange range;
  };
  std::vector<Use> uses;
  std::vector<CanIdRange> ranges;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    const CanDriveProtocol& drive = can_drive_of(a);
    const ScalarValue& node = *a.settings.find("node");
    if (!drive.accepts_bitrate(bus.bitrate))
      node.fail(with_article(drive.device_name) + " cannot run at the " + std::to_string(bus.bitrate) + " bit/s of link '" +
                spec.name + "'; expected one of: " + drive.bitrates_text);
    ranges.clear();
    drive.can_ids(a, bus, ranges);
    for (const CanIdRange& r : ranges) {
      for (const Use& u : uses) {
        const bool overlap = r.first <= u.range.last && u.range.first <= r.last;
        if (!overlap || (r.shared && u.range.shared && u.actuator->drive == a.drive)) continue;
        const std::uint32_t id = std::max(r.first, u.range.first);
        node.fail(std::string(drive.device_name) + " node " + std::to_string(a.device_channel) + " uses CAN id " + hex_id(id) +
                  ", which the " + can_drive_of(*u.actuator).device_name + " at node " +
                  std::to_string(u.actuator->device_channel) + " (line " + std::to_string(u.actuator->where.line) +
                  ") also uses on link '" + spec.name + "'; expected a node whose identifiers are free");
      }
      uses.push_back({&a, r});
    }
  }
}

/// The drive sets of a link: one per drive protocol, actuators in rig order.
std::vector<std::unique_ptr<firmware_iface::CanDrives>> make_drive_sets(const rig::Rig& rig, std::size_t link,
                                                                        const CanBusOptions& bus) {
  std::vector<std::unique_ptr<firmware_iface::CanDrives>> sets;
  for (const CanDriveProtocol* drive : can_drive_protocols()) {
    std::vector<const rig::ActuatorSpec*> mine;
    for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link}))
      if (a.drive == drive->name) mine.push_back(&a);
    if (!mine.empty()) sets.push_back(drive->make_drives(rig, mine, bus));
  }
  return sets;
}

firmware_iface::CanLinkConfig link_config(const rig::Rig& rig, std::size_t link, const CanBusOptions& bus, const std::string& how,
                                          const DriverTuning& tuning) {
  firmware_iface::CanLinkConfig config;
  // A simulated adapter answers from a thread of this process, which a busy machine may keep
  // waiting: give it up to 100 ms. Unlike a servo bus, a late CAN reply only counts toward the
  // drive's silence budget, so this need not cover the worst stall.
  DriverTuning can_tuning = tuning;
  can_tuning.min_reply_timeout_ms = std::min(tuning.min_reply_timeout_ms, 100);
  config.reply_timeout = can_tuning.reply_timeout(std::chrono::milliseconds(bus.reply_timeout_ms));
  config.description = "CAN bus '" + rig.links[link].name + "' (" + how + ")";
  return config;
}

SimulatedDevice simulated_can(const rig::Rig& rig, std::size_t link) {
  auto device = std::make_unique<SimulatedCanBus>(rig, link);
  SimulatedCanBus* d = device.get();
  return {std::move(device),
          [d, &rig](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->device_position(index_on_link(rig, a))); }};
}

}  // namespace

CanBusOptions can_bus_options(const rig::Rig& rig, std::size_t link) {
  const rig::LinkSettings& s = rig.links[link].settings;
  CanBusOptions bus;
  if (const ScalarValue* b = s.find("bitrate")) bus.bitrate = static_cast<int>(b->as_integer("bitrate"));
  if (const ScalarValue* t = s.find("reply_timeout_ms"))
    bus.reply_timeout_ms = static_cast<int>(t->as_integer("reply_timeout_ms"));
  if (const ScalarValue* h = s.find("heartbeat_ms")) bus.heartbeat_ms = static_cast<int>(h->as_integer("heartbeat_ms"));
  const double timeout_s =
      (s.find("heartbeat_timeout_ms") ? static_cast<double>(s.find("heartbeat_timeout_ms")->as_integer("heartbeat_timeout_ms"))
                                      : 3.0 * bus.heartbeat_ms) /
      1000.0;
  if (const ScalarValue* m = s.find("mit_master_id"))
    bus.mit_master_id = static_cast<std::uint32_t>(m->as_integer("mit_master_id"));
  bus.silent_ticks = firmware_iface::silence_budget(timeout_s, rig.rate_hz);
  return bus;
}

const Protocol& can_protocol() {
  static const Protocol p = [] {
    Protocol c{
        "can",
        "CAN bus",
        115200,
        "any standard serial rate (USB adapters such as the CANable ignore it)",
        [](int) { return true; },
        validate_can_settings,
        [](const rig::LinkSpec&, bool) -> AddressRule {
          return {"node", 0, firmware_iface::kCanMaxStandardId, nullptr, nullptr, nullptr, 0, 0, ""};
        },
        false,
        false,
        [](const rig::LinkSpec&) { return true; },
        [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& serial,
           const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
          const CanBusOptions bus = can_bus_options(rig, link);
          auto transport = std::make_unique<firmware_iface::SlcanTransport>(serial, bus.bitrate);
          return std::make_unique<firmware_iface::CanLink>(std::move(transport), make_drive_sets(rig, link, bus),
                                                           link_config(rig, link, bus, "SLCAN on " + serial.name(), tuning));
        },
        simulated_can,
    };
    c.finish_actuator = finish_can_actuator;
    c.validate_link_actuators = validate_can_actuators;
    c.port_is_serial = uses_slcan;
    c.open_link = [](const rig::Rig& rig, std::size_t link,
                     const std::string& port) -> std::unique_ptr<firmware_iface::ActuatorLink> {
      const CanBusOptions bus = can_bus_options(rig, link);
      auto transport = std::make_unique<firmware_iface::SocketCanTransport>(port, bus.bitrate);
      return std::make_unique<firmware_iface::CanLink>(std::move(transport), make_drive_sets(rig, link, bus),
                                                       link_config(rig, link, bus, "SocketCAN " + port, DriverTuning{}));
    };
    c.simulation_runs_during_start = true;
    return c;
  }();
  return p;
}

}  // namespace avar::assembly
