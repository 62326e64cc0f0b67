#include "avar/config/input_map.hpp"

#include <cmath>

#include "avar/core/format.hpp"
#include "yaml_support.hpp"

namespace avar::config {
namespace {

bool control_name_ok(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' || c == '/')) return false;
  return true;
}

std::string control_name(const YamlRef& node, const std::string& what) {
  std::string name = node.as_string(what);
  if (!control_name_ok(name))
    node.fail("expected " + what + " to be a control name (letters, digits, _ . - /), found " + node.describe());
  return name;
}

double in_range(const YamlRef& node, const std::string& what, double low, double high, bool high_open) {
  const double v = node.as_double(what);
  if (v < low || (high_open ? v >= high : v > high))
    node.fail("expected " + what + " from " + format_number(low) + " to " + (high_open ? "below " : "") + format_number(high) +
              ", found " + node.describe());
  return v;
}

std::pair<double, double> number_pair(const YamlRef& node, const std::string& what) {
  if (!node.is_sequence() || node.size() != 2) node.fail("expected " + what + " as [low, high], found " + node.describe());
  return {node[0].as_double(what), node[1].as_double(what)};
}

void read_channel_output(const rig::Rig& rig, const YamlRef& node, const std::string& what, control::ControlMapping& m) {
  if (auto axis = node.find("axis")) axis->fail(what + " drives a channel: an axis applies to a target mapping only");
  const YamlRef channel = node.at("channel", what);
  const std::string channel_name = channel.as_string("the channel of " + what);
  const auto ci = rig.find_channel(channel_name);
  if (!ci) channel.fail("unknown channel '" + channel_name + "'; expected one of the rig's channels: " + rig.channel_names());
  m.channel = *ci;
  const rig::ChannelSpec& c = rig.channels[*ci];
  m.low = c.min;
  m.high = c.max;
  if (m.blend == control::Blend::additive) {
    m.low = 0;  // an offset: none at rest, by default
    m.high = c.max - c.min;
  }
  if (auto range = node.find("range")) {
    if (m.mode == control::MappingMode::relative) range->fail(what + " is relative: it takes a rate, not a range");
    const auto [low, high] = number_pair(*range, "the range of " + what);
    const double span = c.max - c.min;
    for (const double v : {low, high}) {
      if (m.blend == control::Blend::additive && std::abs(v) > span)
        range->fail("expected the range of additive " + what + " (an offset) within the span of channel '" + c.name + "' (±" +
                    format_number(span) + "), found " + range->describe());
      if (m.blend == control::Blend::override && (v < c.min || v > c.max))
        range->fail("expected the range of " + what + " inside the limits of channel '" + c.name + "' [" + format_number(c.min) +
                    ", " + format_number(c.max) + "], found " + range->describe());
    }
    m.low = low;
    m.high = high;
  }
}

/// A goal of the rig's inverse kinematics placed this far from the base is no figure's (metres).
constexpr double kTargetReachM = 100;

void read_target_output(const rig::Rig& rig, const YamlRef& node, const std::string& what, control::ControlMapping& m) {
  if (auto channel = node.find("channel")) channel->fail(what + " drives a target: give a channel or a target, not both");
  const YamlRef target = node.at("target", what);
  const std::string effector = target.as_string("the target of " + what);
  if (!rig.kinematics)
    target.fail("target '" + effector + "' of " + what + " needs the rig's kinematics: section, and this rig has none");
  const kinematics::Model& model = rig.kinematics->model;
  const auto ei = model.find_effector(effector);
  if (!ei) {
    std::string names;
    for (const kinematics::Effector& e : model.effectors()) names += (names.empty() ? "" : ", ") + e.name;
    target.fail("unknown target '" + effector + "'; expected one of the kinematics' effectors: " + names);
  }
  m.output = control::MappingOutput::target;
  m.effector = *ei;
  const YamlRef axis = node.at("axis", what);
  const std::string a = axis.as_string("the axis of " + what);
  if (a == "x") m.axis = 0;
  else if (a == "y") m.axis = 1;
  else if (a == "z") m.axis = 2;
  else axis.fail("expected the axis of " + what + " to be x, y or z (the rig's base frame), found " + axis.describe());
  const YamlRef range = node.at("range", what);
  const auto [low, high] = number_pair(range, "the range of " + what + " (metres)");
  for (const double v : {low, high})
    if (!(std::abs(v) <= kTargetReachM))
      range.fail("expected the range of " + what + " in metres within ±" + format_number(kTargetReachM) + " of the base, found " +
                 range.describe());
  if (m.mode == control::MappingMode::relative && low == high)
    range.fail("expected the range of relative " + what + " (the bounds it moves in) to span two different values, found " +
               range.describe());
  m.low = low;
  m.high = high;
}

control::ControlMapping read_mapping(const rig::Rig& rig, const YamlRef& node, std::size_t index) {
  const std::string what = "mapping " + std::to_string(index + 1) + " of inputs";
  node.expect_map(what);
  node.expect_only_keys({"control", "channel", "target", "axis", "mode", "range", "rate", "input", "invert", "dead_zone", "expo",
                         "smoothing", "hold", "priority", "blend", "crossfade", "timeout"},
                        what);
  control::ControlMapping m;
  m.control = control_name(node.at("control", what), "the control of " + what);
  if (auto mode = node.find("mode")) {
    const std::string s = mode->as_string("the mode of " + what);
    if (s == "relative") m.mode = control::MappingMode::relative;
    else if (s != "absolute")
      mode->fail("expected the mode of " + what + " to be absolute or relative, found " + mode->describe());
  }
  if (auto blend = node.find("blend")) {
    const std::string b = blend->as_string("the blend of " + what);
    if (b == "additive") m.blend = control::Blend::additive;
    else if (b != "override")
      blend->fail("expected the blend of " + what + " to be override or additive, found " + blend->describe());
  }
  if (node.find("target")) {
    read_target_output(rig, node, what, m);
  } else {
    read_channel_output(rig, node, what, m);
  }
  if (auto rate = node.find("rate")) {
    if (m.mode != control::MappingMode::relative) rate->fail(what + " is absolute: a rate applies to mode: relative only");
    m.rate = rate->as_double("the rate of " + what);
    if (!(m.rate > 0))
      rate->fail("expected the rate of " + what + " (channel units/s, or m/s for a target) to be greater than 0, found " +
                 rate->describe());
  } else if (m.mode == control::MappingMode::relative) {
    node.fail("expected a rate (channel units per second at full deflection, or m/s for a target) for relative " + what);
  }
  if (auto input = node.find("input")) {
    const auto span = number_pair(*input, "the input of " + what);
    if (span.first == span.second)
      input->fail("expected the input of " + what + " to span two different values, found " + input->describe());
    m.shape.input = span;
  }
  if (auto invert = node.find("invert")) m.shape.invert = invert->as_bool("invert of " + what);
  if (auto dz = node.find("dead_zone")) m.shape.dead_zone = in_range(*dz, "the dead_zone of " + what, 0, 1, true);
  if (auto expo = node.find("expo")) m.shape.expo = in_range(*expo, "the expo of " + what, 0, 1, false);
  if (auto sm = node.find("smoothing")) m.shape.smoothing_s = in_range(*sm, "the smoothing of " + what + " (s)", 0, 10, false);
  if (auto hold = node.find("hold")) m.hold = control_name(*hold, "the hold control of " + what);
  if (auto priority = node.find("priority")) {
    const long long p = priority->as_integer("the priority of " + what);
    if (p < -999 || p > 999)
      priority->fail("expected the priority of " + what + " from -999 to 999 (the direct channel controls sit at 1000), found " +
                     priority->describe());
    m.priority = static_cast<int>(p);
  }
  if (auto fade = node.find("crossfade")) m.crossfade_s = in_range(*fade, "the crossfade of " + what + " (s)", 0, 60, false);
  if (auto timeout = node.find("timeout")) m.timeout_s = in_range(*timeout, "the timeout of " + what + " (s)", 0, 3600, false);
  return m;
}

}  // namespace

std::vector<std::string> live_effectors(const rig::Rig& rig) {
  std::vector<std::string> names;
  if (rig.kinematics)
    for (const kinematics::Effector& e : rig.kinematics->model.effectors()) names.push_back(e.name);
  return names;
}

std::vector<control::LiveChannel> live_channels(const rig::Rig& rig) {
  std::vector<control::LiveChannel> channels;
  for (const rig::ChannelSpec& c : rig.channels) channels.push_back({c.name, c.min + c.soft_margin, c.max - c.soft_margin});
  return channels;
}

InputMap load_input_map(const rig::Rig& rig, const std::string& path, bool required) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  root.expect_map("the file");
  InputMap map;
  const auto inputs = root.find("inputs");
  if (!inputs) {
    if (required) root.fail("expected an inputs: section (devices and mappings of live controls)");
    return map;
  }
  if (required && rig.file != path) root.expect_only_keys({"inputs"}, "an inputs file");
  map.file = path;
  inputs->expect_map("inputs");
  inputs->expect_only_keys({"devices", "mappings"}, "inputs");
  if (auto devices = inputs->find("devices")) {
    devices->expect_sequence("the devices of inputs");
    for (std::size_t i = 0; i < devices->size(); ++i) map.devices.push_back((*devices)[i].as_string("an input device"));
  }
  if (auto mappings = inputs->find("mappings")) {
    mappings->expect_sequence("the mappings of inputs");
    for (std::size_t i = 0; i < mappings->size(); ++i) {
      map.mappings.push_back(read_mapping(rig, (*mappings)[i], i));
      map.mapping_where.push_back((*mappings)[i].where());
    }
  }
  return map;
}

}  // namespace avar::config
