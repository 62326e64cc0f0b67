#include "avar/core/format.hpp"
#include "avar/config/rig_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "avar/config/yaml_support.hpp"
#include "avar/firmware_iface/serial_transport.hpp"

namespace avar::config {
namespace {

using control::ActuatorSpec;
using control::ChannelSpec;
using control::LinkSpec;
using control::Rig;

double positive(const YamlRef& node, std::string_view what) {
  const double v = node.as_double(what);
  if (v <= 0) node.fail("expected " + std::string(what) + " to be greater than 0, found " + format_number(v));
  return v;
}

ChannelSpec read_channel(const std::string& name, const YamlRef& node) {
  const std::string what = "channel '" + name + "'";
  node.expect_only_keys(
      {"unit", "min", "max", "rest", "max_velocity", "max_acceleration", "max_jerk", "soft_margin", "ramp_velocity",
       "tracking_tolerance"},
      what);
  ChannelSpec c;
  c.name = name;
  c.where = node.where();
  c.unit = node.find("unit") ? node.at("unit", what).as_string("the unit of " + what) : "";
  c.min = node.at("min", what).as_double("min of " + what);
  const YamlRef max = node.at("max", what);
  c.max = max.as_double("max of " + what);
  if (!(c.max > c.min)) max.fail("expected max of " + what + " to be greater than its min " + format_number(c.min) + ", found " + format_number(c.max));
  const YamlRef rest = node.at("rest", what);
  c.rest = rest.as_double("rest of " + what);
  if (c.rest < c.min || c.rest > c.max)
    rest.fail("expected rest of " + what + " inside its limits [" + format_number(c.min) + ", " + format_number(c.max) + "], found " + format_number(c.rest));
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

int maestro_channels_for_model(const YamlRef& node) {
  const std::string model = node.as_string("the Maestro model");
  if (model == "micro6") return 6;
  if (model == "mini12") return 12;
  if (model == "mini18") return 18;
  if (model == "mini24") return 24;
  node.fail("unknown Maestro model " + node.describe() + "; expected one of: micro6, mini12, mini18, mini24");
}

LinkSpec read_link(const std::string& name, const YamlRef& node) {
  const std::string what = "link '" + name + "'";
  node.expect_only_keys({"port", "baud", "watchdog_ms", "maestro"}, what);
  LinkSpec link;
  link.name = name;
  link.where = node.where();
  link.port = node.at("port", what).as_string("the port of " + what + " (a device path such as /dev/ttyACM0, or sim)");
  if (auto baud = node.find("baud")) {
    const long long b = baud->as_integer("the baud rate of " + what);
    if (b <= 0 || b > 4'000'000 || !firmware_iface::SerialTransport::is_supported_baud(static_cast<int>(b)))
      baud->fail("expected a standard serial baud rate (9600, 19200, 38400, 57600, 115200, 230400, 1000000...), found " + baud->describe());
    link.baud = static_cast<int>(b);
  }
  if (auto w = node.find("watchdog_ms")) {
    const double ms = w->as_double("watchdog_ms of " + what);
    if (ms < 1 || ms > 60000) w->fail("expected watchdog_ms of " + what + " from 1 to 60000 milliseconds, found " + w->describe());
    link.watchdog_s = ms / 1000.0;
  }
  if (auto m = node.find("maestro")) {
    const std::string mwhat = "the maestro settings of " + what;
    m->expect_only_keys({"model", "device_number", "crc", "baud_detect"}, mwhat);
    if (auto model = m->find("model")) link.maestro.channel_count = maestro_channels_for_model(*model);
    if (auto dev = m->find("device_number")) {
      const long long d = dev->as_integer("the device number");
      if (d < 0 || d > 127) dev->fail("expected a device number from 0 to 127, found " + dev->describe());
      link.maestro.pololu_form = true;
      link.maestro.device_number = static_cast<std::uint8_t>(d);
    }
    if (auto crc = m->find("crc")) link.maestro.crc = crc->as_bool("crc");
    if (auto bd = m->find("baud_detect")) link.maestro.baud_detect = bd->as_bool("baud_detect");
  }
  return link;
}

ActuatorSpec read_actuator(const Rig& rig, const YamlRef& node, std::size_t index) {
  const std::string what = "actuator " + std::to_string(index + 1);
  node.expect_only_keys(
      {"channel", "protocol", "link", "device_channel", "calibration", "speed", "acceleration", "failsafe"}, what);
  ActuatorSpec a;
  a.where = node.where();

  const YamlRef channel = node.at("channel", what);
  const std::string channel_name = channel.as_string("the channel of " + what);
  const auto ci = rig.find_channel(channel_name);
  if (!ci) channel.fail("unknown channel '" + channel_name + "'; expected one of the rig's channels: " + rig.channel_names());
  a.channel = *ci;
  const ChannelSpec& ch = rig.channels[a.channel];

  const YamlRef protocol = node.at("protocol", what);
  if (protocol.as_string("the protocol of " + what) != "maestro")
    protocol.fail("unknown protocol " + protocol.describe() + "; expected one of: maestro");

  const YamlRef link = node.at("link", what);
  const std::string link_name = link.as_string("the link of " + what);
  const auto li = rig.find_link(link_name);
  if (!li) {
    std::string names;
    for (const LinkSpec& l : rig.links) names += (names.empty() ? "" : ", ") + l.name;
    link.fail("unknown link '" + link_name + "'; expected one of the rig's links: " + names);
  }
  a.link = *li;

  const YamlRef dc = node.at("device_channel", what);
  const long long device_channel = dc.as_integer("the device channel of " + what);
  const int count = rig.links[a.link].maestro.channel_count;
  if (device_channel < 0 || device_channel >= count)
    dc.fail("expected a device channel from 0 to " + std::to_string(count - 1) + " (the Maestro on link '" + link_name +
            "' has " + std::to_string(count) + " channels), found " + dc.describe());
  a.device_channel = static_cast<int>(device_channel);

  const YamlRef cal = node.at("calibration", what);
  cal.expect_only_keys({"min_us", "max_us", "reverse", "trim_us"}, "the calibration of " + what);
  a.calibration.channel_min = ch.min;
  a.calibration.channel_max = ch.max;
  auto pulse = [&](const char* key) {
    const YamlRef n = cal.at(key, "the calibration of " + what);
    const double us = n.as_double(std::string(key) + " (pulse width in microseconds)");
    if (us < 64 || us > 4000) n.fail(std::string("expected ") + key + " to be a pulse width from 64 to 4000 µs, found " + n.describe());
    return us;
  };
  a.calibration.device_at_min = pulse("min_us");
  a.calibration.device_at_max = pulse("max_us");
  if (a.calibration.device_at_min == a.calibration.device_at_max)
    cal.fail("expected min_us and max_us to differ (both are " + format_number(a.calibration.device_at_min) + " µs)");
  if (auto r = cal.find("reverse")) a.calibration.reverse = r->as_bool("reverse");
  if (auto t = cal.find("trim_us")) {
    a.calibration.trim = t->as_double("trim_us");
    if (a.calibration.device_low() < 64 || a.calibration.device_high() > 4000)
      t->fail("expected the trimmed pulse window to stay within 64 to 4000 µs, found [" + format_number(a.calibration.device_low()) +
              ", " + format_number(a.calibration.device_high()) + "] µs");
  }
  if (auto f = node.find("failsafe")) {
    const std::string action = f->as_string("the fail-safe action of " + what);
    if (action == "hold") a.failsafe = control::Failsafe::hold;
    else if (action == "rest") a.failsafe = control::Failsafe::rest;
    else if (action == "release") a.failsafe = control::Failsafe::release;
    else f->fail("unknown fail-safe action " + f->describe() + "; expected one of: hold, rest, release");
  }
  if (auto s = node.find("speed")) a.speed_limit = positive(*s, "the speed limit of " + what + " (" + ch.unit + "/s)");
  if (auto s = node.find("acceleration"))
    a.acceleration_limit = positive(*s, "the acceleration limit of " + what + " (" + ch.unit + "/s²)");
  return a;
}

}  // namespace

control::Rig load_rig_file(const std::string& path) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  root.expect_only_keys({"name", "rate_hz", "links", "channels", "actuators"}, "the rig file");

  Rig rig;
  rig.file = path;
  rig.name = root.find("name") ? root.at("name", "the rig file").as_string("the rig's name")
                               : std::filesystem::path(path).stem().string();
  if (auto rate = root.find("rate_hz")) {
    rig.rate_hz = rate->as_double("rate_hz");
    if (rig.rate_hz < 1 || rig.rate_hz > 1000) rate->fail("expected rate_hz from 1 to 1000 ticks per second, found " + rate->describe());
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
    if (!used.insert({a.link, a.device_channel}).second)
      node.at("device_channel", "").fail("device channel " + std::to_string(a.device_channel) + " of link '" +
                                         rig.links[a.link].name + "' is used by two actuators");
    rig.actuators.push_back(std::move(a));
  }
  return rig;
}

}  // namespace avar::config
