#include "avar/core/format.hpp"
#include "avar/config/rig_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "rig_kinematics.hpp"
#include "idle_section.hpp"
#include "viseme_table.hpp"
#include "yaml_support.hpp"
#include "avar/rig/protocol_schema.hpp"

namespace avar::config {
namespace {

using rig::ActuatorSpec;
using rig::ChannelSpec;
using rig::LinkSpec;
using rig::Rig;

/// The highest GPIO line offset a rig may name (chips are checked when opened).
constexpr long long kMaxGpioLine = 1023;

double positive(const YamlRef& node, std::string_view what) {
  const double v = node.as_double(what);
  if (v <= 0) node.fail("expected " + std::string(what) + " to be greater than 0, found " + format_number(v));
  return v;
}

constexpr std::string_view kMotionKeys[] = {"max_velocity", "max_acceleration", "max_jerk",
                                            "soft_margin",  "ramp_velocity",    "tracking_tolerance"};

/// A digital channel: 0 (off) or 1 (on), switching at once: no motion limits.
ChannelSpec read_digital_channel(const std::string& name, const YamlRef& node) {
  const std::string what = "digital channel '" + name + "'";
  for (std::string_view key : kMotionKeys)
    if (auto k = node.find(key))
      k->fail("a digital channel switches at once, so " + std::string(key) + " does not apply to " + what +
              "; remove it (or make the channel analog)");
  node.expect_only_keys({"kind", "unit", "min", "max", "rest"}, what);
  ChannelSpec c;
  c.name = name;
  c.where = node.where();
  c.kind = rig::ChannelKind::digital;
  c.unit = node.find("unit") ? node.at("unit", what).as_string("the unit of " + what) : "";
  const auto fixed = [&](const char* key, double wanted) {
    if (auto k = node.find(key); k && k->as_double(std::string(key) + " of " + what) != wanted)
      k->fail("expected " + std::string(key) + " of " + what + " to be " + format_number(wanted) +
              " (a digital channel is 0, off, or 1, on), found " + k->describe());
  };
  fixed("min", 0);
  fixed("max", 1);
  c.min = 0;
  c.max = 1;
  if (auto rest = node.find("rest")) {
    c.rest = rest->as_double("rest of " + what);
    if (c.rest != 0 && c.rest != 1)
      rest->fail("expected rest of " + what + " to be 0 (off) or 1 (on), found " + rest->describe());
  }
  const double inf = std::numeric_limits<double>::infinity();
  c.max_velocity = c.max_acceleration = c.max_jerk = c.ramp_velocity = inf;
  return c;
}

ChannelSpec read_channel(const std::string& name, const YamlRef& node) {
  if (auto kind = node.find("kind")) {
    const std::string k = kind->as_string("the kind of channel '" + name + "'");
    if (k == "digital") return read_digital_channel(name, node);
    if (k != "analog")
      kind->fail("unknown channel kind " + kind->describe() + "; expected analog (moves within limits) or digital (0 off, 1 on)");
  }
  const std::string what = "channel '" + name + "'";
  node.expect_only_keys({"kind", "unit", "min", "max", "rest", "max_velocity", "max_acceleration", "max_jerk", "soft_margin",
                         "ramp_velocity", "tracking_tolerance"},
                        what);
  ChannelSpec c;
  c.name = name;
  c.where = node.where();
  c.unit = node.find("unit") ? node.at("unit", what).as_string("the unit of " + what) : "";
  c.min = node.at("min", what).as_double("min of " + what);
  const YamlRef max = node.at("max", what);
  c.max = max.as_double("max of " + what);
  if (!(c.max > c.min))
    max.fail("expected max of " + what + " to be greater than its min " + format_number(c.min) + ", found " +
             format_number(c.max));
  const YamlRef rest = node.at("rest", what);
  c.rest = rest.as_double("rest of " + what);
  if (c.rest < c.min || c.rest > c.max)
    rest.fail("expected rest of " + what + " inside its limits [" + format_number(c.min) + ", " + format_number(c.max) +
              "], found " + format_number(c.rest));
  const double range = c.max - c.min;
  // Defaults: a hobby servo crosses its range in ~0.25 s, reaches that speed in ~0.1 s and its
  // full acceleration in ~0.05 s; the soft start and stop take ~2 s for the whole range.
  const auto limit_or = [&](const char* key, double fallback) {
    return node.find(key) ? positive(node.at(key, what), std::string(key) + " of " + what) : fallback;
  };
  c.max_velocity = limit_or("max_velocity", 4.0 * range);
  c.max_acceleration = limit_or("max_acceleration", 10.0 * c.max_velocity);
  c.max_jerk = limit_or("max_jerk", 20.0 * c.max_acceleration);
  if (auto margin = node.find("soft_margin")) {
    c.soft_margin = margin->as_double("soft_margin of " + what);
    if (c.soft_margin < 0 || 2 * c.soft_margin >= range)
      margin->fail("expected soft_margin of " + what + " from 0 to less than half the range (" + format_number(range / 2) +
                   "), found " + margin->describe());
  }
  if (auto tol = node.find("tracking_tolerance")) c.tracking_tolerance = positive(*tol, "tracking_tolerance of " + what);
  c.ramp_velocity = node.find("ramp_velocity") ? positive(node.at("ramp_velocity", what), "ramp_velocity of " + what)
                                               : std::min(c.max_velocity, 0.5 * range);
  return c;
}

/// The link's protocol block as written, for its registry entry to interpret.
rig::LinkSettings read_settings(const YamlRef& block, const std::string& what) {
  rig::LinkSettings settings;
  settings.where = block.where();
  settings.what = what;
  if (block.node.IsNull()) return settings;
  for (auto it = block.node.begin(); it != block.node.end(); ++it) {
    const YamlRef key{it->first, block.file};
    settings.entries.push_back({it->first.Scalar(), key.where(), YamlRef{it->second, block.file}.scalar()});
  }
  return settings;
}

LinkSpec read_link(const std::string& name, const YamlRef& node) {
  const std::string what = "link '" + name + "'";
  const std::string names = rig::protocol_names();
  std::vector<std::string_view> keys{"port", "baud", "watchdog_ms"};
  for (const rig::ProtocolSchema* p : rig::schemas()) keys.push_back(p->name);
  node.expect_only_keys(keys, what);
  LinkSpec link;
  link.name = name;
  link.where = node.where();
  const std::string port_what = "the port of " + what + " (a device path such as /dev/ttyACM0, or sim)";
  const auto port = node.find("port");
  if (port) link.port = port->as_string(port_what);

  // The protocol is the one settings block the link has: maestro: {...}, dynamixel: {} ...
  std::optional<YamlRef> settings;
  const rig::ProtocolSchema* protocol = nullptr;
  for (const rig::ProtocolSchema* p : rig::schemas()) {
    auto block = node.find(p->name);
    if (!block) continue;
    if (settings) block->fail(what + " names two protocols; expected exactly one of: " + names);
    settings = block;
    protocol = p;
  }
  if (!settings)
    node.fail("expected " + what + " to name its protocol with a settings block, one of: " + names +
              " (for example `dynamixel: {}`)");
  link.protocol = protocol->name;
  if (!settings->node.IsNull() && !settings->node.IsMap())
    settings->fail("expected the " + link.protocol + " settings of " + what + " to be a map (use {} for the defaults)");

  link.baud = protocol->default_baud;
  if (auto baud = node.find("baud")) link.baud = rig::checked_baud(*protocol, baud->scalar(), "the baud rate of " + what);
  if (auto w = node.find("watchdog_ms")) {
    const double ms = w->as_double("watchdog_ms of " + what);
    if (ms < 1 || ms > 60000)
      w->fail("expected watchdog_ms of " + what + " from 1 to 60000 milliseconds, found " + w->describe());
    link.watchdog_s = ms / 1000.0;
  }
  const rig::LinkSettings written = read_settings(*settings, "the " + link.protocol + " settings of " + what);
  // A link whose device is found otherwise (a Maestro on USB by its serial number) needs no port.
  if (!port && !(protocol->port_optional && protocol->port_optional(written))) node.at("port", what).as_string(port_what);
  link.options = protocol->parse(link, written);
  return link;
}

/// The keys every actuator may have, whatever its link.
constexpr std::string_view kActuatorKeys[] = {"channel", "protocol",    "link",  "device_channel", "id",      "address",
                                              "fine",    "calibration", "speed", "acceleration",   "failsafe"};

/// On a bus of drives, the keys its protocol interprets (everything but the common ones), as
/// written; the protocol then parses them.
rig::LinkSettings read_drive_settings(const YamlRef& node, const std::string& what, const rig::AddressRule& rule) {
  rig::LinkSettings own;
  own.where = node.where();
  own.what = "the settings of " + what;
  for (auto it = node.node.begin(); it != node.node.end(); ++it) {
    const std::string key = it->first.Scalar();
    // The protocol and the address stay in too: the drive's entry checks them.
    if (key != "protocol" && key != rule.key &&
        std::find(std::begin(kActuatorKeys), std::end(kActuatorKeys), key) != std::end(kActuatorKeys))
      continue;
    const YamlRef value{it->second, node.file};
    own.entries.push_back({key, YamlRef{it->first, node.file}.where(), value.scalar()});
  }
  return own;
}

/// "active_low" for messages: the keys a protocol's actuators take of their own.
std::string own_keys(const rig::ProtocolSchema& p) {
  std::string list;
  for (std::string_view k : p.actuator_keys) list += (list.empty() ? "" : ", ") + std::string(k);
  return list;
}

ActuatorSpec read_actuator(const Rig& rig, const YamlRef& node, std::size_t index) {
  const std::string what = "actuator " + std::to_string(index + 1);
  ActuatorSpec a;
  a.where = node.where();

  const YamlRef channel = node.at("channel", what);
  const std::string channel_name = channel.as_string("the channel of " + what);
  const auto ci = rig.find_channel(channel_name);
  if (!ci) channel.fail("unknown channel '" + channel_name + "'; expected one of the rig's channels: " + rig.channel_names());
  a.channel = rig::ChannelIndex{*ci};
  const ChannelSpec& ch = rig.channel(a.channel);

  const YamlRef link = node.at("link", what);
  const std::string link_name = link.as_string("the link of " + what);
  const auto li = rig.find_link(link_name);
  if (!li) {
    std::string names;
    for (const LinkSpec& l : rig.links) names += (names.empty() ? "" : ", ") + l.name;
    link.fail("unknown link '" + link_name + "'; expected one of the rig's links: " + names);
  }
  a.link = rig::LinkIndex{*li};
  const LinkSpec& spec = rig.link(a.link);
  const rig::ProtocolSchema& link_protocol = rig::schema_of(spec);
  const std::string& protocol_name = spec.protocol;
  const bool drive_bus = link_protocol.finish_actuator != nullptr;
  // A bus of drives takes keys of its own, which its protocol checks (finish_actuator); other
  // protocols may name a few of their own (actuator_keys) besides their address key.
  if (!drive_bus) {
    std::vector<std::string_view> keys(std::begin(kActuatorKeys), std::end(kActuatorKeys));
    const std::string_view address_key = link_protocol.address_rule(spec, false).key;
    if (std::find(keys.begin(), keys.end(), address_key) == keys.end()) keys.push_back(address_key);
    keys.insert(keys.end(), link_protocol.actuator_keys.begin(), link_protocol.actuator_keys.end());
    node.expect_only_keys(keys, what);
  }
  if (drive_bus && ch.digital())
    channel.fail("channel '" + ch.name + "' is digital (0 off, 1 on); a drive on " + protocol_name + " link '" + spec.name +
                 "' needs an analog channel");
  if (drive_bus) {
    if (auto cal = node.find("calibration"))
      cal->fail("actuators on " + protocol_name + " link '" + link_name +
                "' take no calibration block; their gear_ratio, units_per_turn and zero map the channel to the motor");
    if (auto fine = node.find("fine"))
      fine->fail("fine (16-bit DMX) applies to dmx links only; link '" + link_name + "' speaks " + protocol_name);
  } else if (auto protocol = node.find("protocol")) {
    const std::string p = protocol->as_string("the protocol of " + what);
    if (!rig::find_schema(p))
      protocol->fail("unknown protocol " + protocol->describe() + "; expected one of: " + rig::protocol_names());
    if (p != protocol_name)
      protocol->fail("link '" + link_name + "' speaks " + protocol_name + ", not " + p + "; expected protocol: " + protocol_name);
  }

  if (auto fine = node.find("fine")) {
    if (!link_protocol.has_fine_addresses)
      fine->fail("fine (16-bit DMX) applies to dmx links only; link '" + link_name + "' speaks " + protocol_name);
    a.fine = fine->as_bool("fine");
  }
  const rig::AddressRule rule = link_protocol.address_rule(spec, a.fine);
  for (const char* key : {"device_channel", "id", "address"})
    if (std::string(key) != rule.key)
      if (auto wrong = node.find(key))
        wrong->fail(std::string(key) + " does not address a " + protocol_name + " actuator; expected " + rule.key);
  const YamlRef dc = node.at(rule.key, what + " on " + protocol_name + " link '" + link_name + "'");
  const long long address = dc.as_integer(std::string("the ") + rule.key + " of " + what);
  if (address < rule.low || address > rule.high)
    dc.fail("expected " + std::string(rule.key) + " from " + std::to_string(rule.low) + " to " + std::to_string(rule.high) +
            " on " + protocol_name + " link '" + link_name + "', found " + dc.describe());
  a.device_channel = static_cast<int>(address);
  a.address_where = dc.where();

  a.calibration.channel_min = ch.min;
  a.calibration.channel_max = ch.max;
  a.calibration.device_at_min = rule.device_low;
  a.calibration.device_at_max = rule.device_high;
  const std::string cwhat = "the calibration of " + what;
  auto device_value = [&](const YamlRef& n, const char* key) {
    const double v = n.as_double(std::string(key) + " (" + rule.unit + ")");
    if (v < rule.device_low || v > rule.device_high)
      n.fail(std::string("expected ") + key + " from " + format_number(rule.device_low) + " to " +
             format_number(rule.device_high) + " " + rule.unit + ", found " + n.describe());
    return v;
  };
  if (!rule.cal_min)
    if (auto cal = node.find("calibration"))
      cal->fail("actuators on " + protocol_name + " link '" + link_name + "' take no calibration block" +
                (link_protocol.actuator_keys.empty()
                     ? ""
                     : "; their keys are: " + std::string(rule.key) + ", " + own_keys(link_protocol)));
  // A DMX dimmer spans its whole range by default; servos must be calibrated.
  const auto cal_node =
      link_protocol.needs_calibration ? std::optional<YamlRef>(node.at("calibration", what)) : node.find("calibration");
  if (cal_node) {
    const YamlRef& cal = *cal_node;
    cal.expect_only_keys({rule.cal_min, rule.cal_max, "reverse", rule.trim}, cwhat);
    a.calibration.device_at_min = device_value(cal.at(rule.cal_min, cwhat), rule.cal_min);
    a.calibration.device_at_max = device_value(cal.at(rule.cal_max, cwhat), rule.cal_max);
    if (a.calibration.device_at_min == a.calibration.device_at_max)
      cal.fail(std::string("expected ") + rule.cal_min + " and " + rule.cal_max + " to differ (both are " +
               format_number(a.calibration.device_at_min) + " " + rule.unit + ")");
    if (auto r = cal.find("reverse")) a.calibration.reverse = r->as_bool("reverse");
    if (auto t = cal.find(rule.trim)) {
      a.calibration.trim = t->as_double(rule.trim);
      if (a.calibration.device_low() < rule.device_low || a.calibration.device_high() > rule.device_high)
        t->fail("expected the trimmed window to stay within " + format_number(rule.device_low) + " to " +
                format_number(rule.device_high) + " " + rule.unit + ", found [" + format_number(a.calibration.device_low()) +
                ", " + format_number(a.calibration.device_high()) + "]");
    }
  }
  if (auto f = node.find("failsafe")) {
    const std::string action = f->as_string("the fail-safe action of " + what);
    if (action == "hold") a.failsafe = rig::Failsafe::hold;
    else if (action == "rest") a.failsafe = rig::Failsafe::rest;
    else if (action == "release") a.failsafe = rig::Failsafe::release;
    else f->fail("unknown fail-safe action " + f->describe() + "; expected one of: hold, rest, release");
  }
  if (auto s = node.find("speed")) a.speed_limit = positive(*s, "the speed limit of " + what + " (" + ch.unit + "/s)");
  if (auto s = node.find("acceleration"))
    a.acceleration_limit = positive(*s, "the acceleration limit of " + what + " (" + ch.unit + "/s²)");
  if (drive_bus) {
    link_protocol.finish_actuator(rig, a, read_drive_settings(node, what, rule));
  } else if (link_protocol.check_actuator) {
    rig::LinkSettings own;
    own.where = node.where();
    own.what = "the settings of " + what;
    for (std::string_view key : link_protocol.actuator_keys)
      if (auto k = node.find(key)) own.entries.push_back({std::string(key), k->where(), k->scalar()});
    link_protocol.check_actuator(rig, a, own);
  }
  return a;
}

/// One entry of `digital_inputs:`.
rig::DigitalInputSpec read_digital_input(const std::string& name, const YamlRef& node) {
  const std::string what = "digital input '" + name + "'";
  node.expect_only_keys({"chip", "line", "active_low", "bias", "debounce_ms", "role"}, what);
  rig::DigitalInputSpec in;
  in.name = name;
  in.where = node.where();
  in.chip = node.at("chip", what).as_string("the chip of " + what + " (gpiochip0, a chip's label or path, or sim)");
  const YamlRef line = node.at("line", what);
  const long long offset = line.as_integer("the line of " + what);
  if (offset < 0 || offset > kMaxGpioLine)
    line.fail("expected the line of " + what + " from 0 to " + std::to_string(kMaxGpioLine) + ", found " + line.describe());
  in.line = static_cast<unsigned>(offset);
  if (auto low = node.find("active_low")) in.active_low = low->as_bool("active_low of " + what);
  if (auto bias = node.find("bias")) {
    const std::string b = bias->as_string("the bias of " + what);
    if (b == "as_is") in.bias = firmware_iface::GpioBias::as_is;
    else if (b == "disabled") in.bias = firmware_iface::GpioBias::disabled;
    else if (b == "pull_up") in.bias = firmware_iface::GpioBias::pull_up;
    else if (b == "pull_down") in.bias = firmware_iface::GpioBias::pull_down;
    else
      bias->fail("unknown bias " + bias->describe() + " of " + what + "; expected one of: as_is, disabled, pull_up, pull_down");
  }
  if (auto d = node.find("debounce_ms")) {
    const double ms = d->as_double("debounce_ms of " + what);
    if (ms < 0 || ms > 1000) d->fail("expected debounce_ms of " + what + " from 0 to 1000 milliseconds, found " + d->describe());
    in.debounce_s = ms / 1000.0;
  }
  const YamlRef role = node.at("role", what);
  const std::string r = role.as_string("the role of " + what);
  if (r == "estop") in.role = rig::InputRole::estop;
  else if (r == "control") in.role = rig::InputRole::control;
  else if (r == "start") in.role = rig::InputRole::start;
  else
    role.fail("unknown role " + role.describe() + " of " + what +
              "; expected one of: estop (stops the figure), control (a live input), start (a show start button)");
  return in;
}

/// A line is one input or one output, never both.
void check_gpio_lines(const Rig& rig, const std::vector<YamlRef>& input_nodes) {
  for (std::size_t i = 0; i < rig.digital_inputs.size(); ++i) {
    const rig::DigitalInputSpec& in = rig.digital_inputs[i];
    const YamlRef line = input_nodes[i].at("line", "");
    for (std::size_t j = 0; j < i; ++j)
      if (rig.digital_inputs[j].chip == in.chip && rig.digital_inputs[j].line == in.line)
        line.fail("line " + std::to_string(in.line) + " of chip '" + in.chip + "' is already digital input '" +
                  rig.digital_inputs[j].name + "' (line " + std::to_string(rig.digital_inputs[j].where.line) + ")");
    for (const rig::ActuatorSpec& a : rig.actuators) {
      const LinkSpec& link = rig.link(a.link);
      if (link.protocol == "gpio" && link.port == in.chip && a.device_channel == static_cast<int>(in.line))
        line.fail("line " + std::to_string(in.line) + " of chip '" + in.chip + "' is already the output of channel '" +
                  rig.channel(a.channel).name + "' on link '" + link.name + "' (line " + std::to_string(a.where.line) + ")");
    }
  }
}

rig::Rig rig_from_yaml(const YAML::Node& root_node, const std::string& path) {
  const YamlRef root{root_node, &path};
  // `inputs:` is read by load_input_map (input_map.hpp).
  root.expect_only_keys(
      {"name", "rate_hz", "links", "channels", "actuators", "kinematics", "digital_inputs", "inputs", "visemes", "idle"},
      "the rig file");

  Rig rig;
  rig.file = path;
  rig.name = root.find("name") ? root.at("name", "the rig file").as_string("the rig's name")
                               : std::filesystem::path(path).stem().string();
  if (auto rate = root.find("rate_hz")) {
    rig.rate_hz = rate->as_double("rate_hz");
    if (rig.rate_hz < 1 || rig.rate_hz > 1000)
      rate->fail("expected rate_hz from 1 to 1000 ticks per second, found " + rate->describe());
  }

  const YamlRef links = root.at("links", "the rig file");
  links.expect_map("links (a map of link name to its port and settings)");
  if (links.size() == 0) links.fail("expected at least one link");
  for (auto it = links.node.begin(); it != links.node.end(); ++it)
    rig.links.push_back(read_link(it->first.Scalar(), YamlRef{it->second, &path}));

  const YamlRef channels = root.at("channels", "the rig file");
  channels.expect_map("channels (a map of channel name to its unit and limits)");
  if (channels.size() == 0) channels.fail("expected at least one channel");
  for (auto it = channels.node.begin(); it != channels.node.end(); ++it) {
    const std::string name = it->first.Scalar();
    if (rig.find_channel(name)) YamlRef{it->first, &path}.fail("channel '" + name + "' is defined twice");
    rig.channels.push_back(read_channel(name, YamlRef{it->second, &path}));
  }

  const YamlRef actuators = root.at("actuators", "the rig file");
  actuators.expect_sequence("actuators");
  std::set<std::pair<std::size_t, int>> used;
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const YamlRef node = actuators[i];
    ActuatorSpec a = read_actuator(rig, node, i);
    const LinkSpec& link = rig.link(a.link);
    const rig::ProtocolSchema& protocol = rig::schema_of(link);
    // A bus of drives checks its identifiers itself, once every actuator is read.
    if (protocol.validate_link_actuators) {
      rig.actuators.push_back(std::move(a));
      continue;
    }
    const rig::AddressRule rule = protocol.address_rule(link, a.fine);
    // A 16-bit DMX channel takes two slots.
    for (int slot = a.device_channel; slot <= a.device_channel + (a.fine ? 1 : 0); ++slot)
      if (!used.insert({a.link.value, slot}).second)
        node.at(rule.key, "")
            .fail(std::string(rule.key) + " " + std::to_string(slot) + " of " + link.protocol + " link '" + link.name +
                  "' is used by two actuators");
    rig.actuators.push_back(std::move(a));
  }
  for (std::size_t i = 0; i < rig.links.size(); ++i)
    if (const auto check = rig::schema_of(rig.links[i]).validate_link_actuators) check(rig, i);
  if (auto kin = root.find("kinematics")) rig.kinematics = read_rig_kinematics(rig, *kin);
  if (auto inputs = root.find("digital_inputs")) {
    inputs->expect_map("digital_inputs (a map of input name to its chip, line and role)");
    std::vector<YamlRef> nodes;
    for (auto it = inputs->node.begin(); it != inputs->node.end(); ++it) {
      const std::string name = it->first.Scalar();
      for (const rig::DigitalInputSpec& other : rig.digital_inputs)
        if (other.name == name) YamlRef{it->first, &path}.fail("digital input '" + name + "' is defined twice");
      nodes.push_back(YamlRef{it->second, &path});
      rig.digital_inputs.push_back(read_digital_input(name, nodes.back()));
    }
    check_gpio_lines(rig, nodes);
  }
  // The lip-sync poses (`avar visemes` reads them): validated with the rest of the file.
  if (auto visemes = root.find("visemes")) (void)detail::read_rig_viseme_table(*visemes, rig);
  // Read again by load_idle_section when a run uses it; checked here with the rest of the file.
  if (auto idle = root.find("idle")) (void)read_idle_section(rig, *idle);
  return rig;
}

}  // namespace

rig::Rig load_rig_file(const std::string& path) { return rig_from_yaml(load_yaml_file(path), path); }

rig::Rig load_rig_text(const std::string& text, const std::string& path) {
  return rig_from_yaml(parse_yaml_text(text, path), path);
}

}  // namespace avar::config
