#include "avar/config/retarget_map.hpp"

#include <cmath>
#include <map>

#include "avar/core/format.hpp"
#include "yaml_support.hpp"

namespace avar::config {
namespace {

int retarget_axis(const YamlRef& node, const std::string& what) {
  const std::string s = node.as_string(what);
  if (s == "x") return 0;
  if (s == "y") return 1;
  if (s == "z") return 2;
  node.fail("expected " + what + " to be x, y or z, found " + node.describe());
}

double retarget_number(const YamlRef& parent, std::string_view key, const std::string& what, double fallback) {
  const auto node = parent.find(key);
  return node ? node->as_double(what) : fallback;
}

/// The binding's source joint: its name and where it stands (joints are checked at bake time).
void read_source_joint(const YamlRef& node, const std::string& what, std::string& name, SourceLocation& where) {
  const YamlRef joint = node.at("joint", what + " (the source joint)");
  name = joint.as_string("the joint of " + what);
  where = joint.where();
}

mocap::RotationBinding read_rotation(const rig::Rig& rig, const YamlRef& node, const std::string& what) {
  node.expect_only_keys({"joint", "channel", "axis", "order", "relative_to", "scale", "offset", "reverse", "units"}, what);
  mocap::RotationBinding b;
  b.where = node.where();
  read_source_joint(node, what, b.joint, b.joint_where);
  const YamlRef channel = node.at("channel", what + " (the rig channel it drives)");
  b.channel = channel.as_string("the channel of " + what);
  const auto ci = rig.find_channel(b.channel);
  if (!ci) channel.fail("unknown channel '" + b.channel + "'; expected one of the rig's channels: " + rig.channel_names());
  const rig::ChannelSpec& c = rig.channels[*ci];
  if (c.digital()) channel.fail("channel '" + b.channel + "' is digital (on/off); expected an analog channel for a rotation");
  b.axis = retarget_axis(node.at("axis", what + " (which Euler angle: x, y or z)"), "the axis of " + what);
  const YamlRef order = node.at("order", what + " (the Euler decomposition order, e.g. zxy)");
  const auto o = playback::euler_order_from_name(order.as_string("the order of " + what));
  if (!o) order.fail("expected the order of " + what + " to be one of xyz, xzy, yxz, yzx, zxy, zyx, found " + order.describe());
  b.order = *o;
  if (auto rel = node.find("relative_to")) {
    const std::string s = rel->as_string("relative_to of " + what);
    if (s == "first_frame") b.relative_to = mocap::RelativeTo::first_frame;
    else if (s != "rest") rel->fail("expected relative_to of " + what + " to be rest or first_frame, found " + rel->describe());
  }
  b.scale = retarget_number(node, "scale", "the scale of " + what, 1);
  if (b.scale == 0)
    node.at("scale", what).fail("expected a scale other than 0 for " + what + " (it would hold the channel still)");
  b.offset = retarget_number(node, "offset", "the offset of " + what + " (channel units)", 0);
  if (auto reverse = node.find("reverse")) b.reverse = reverse->as_bool("reverse of " + what);
  const bool angular = c.unit == "deg" || c.unit == "rad";
  b.units = c.unit == "rad" ? mocap::AngleUnit::rad : mocap::AngleUnit::deg;
  if (auto units = node.find("units")) {
    const std::string u = units->as_string("the units of " + what);
    if (u != "deg" && u != "rad") units->fail("expected the units of " + what + " to be deg or rad, found " + units->describe());
    if (angular && u != c.unit)
      units->fail("found units " + u + " for channel '" + c.name + "', which is in " + c.unit + "; expected " + c.unit +
                  " (or leave units out)");
    b.units = u == "rad" ? mocap::AngleUnit::rad : mocap::AngleUnit::deg;
  }
  return b;
}

void read_axes(const YamlRef& node, const std::string& what, mocap::PositionBinding& b) {
  if (!node.is_sequence() || node.size() != 3)
    node.fail("expected the axes of " + what + " as [a, b, c], the file axis (x, y, z, -x, -y or -z) for each rig axis, found " +
              node.describe());
  bool used[3] = {false, false, false};
  for (std::size_t i = 0; i < 3; ++i) {
    const YamlRef item = node[i];
    std::string s = item.as_string("an axis of " + what);
    double sign = 1;
    if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
      sign = s[0] == '-' ? -1 : 1;
      s.erase(0, 1);
    }
    if (s != "x" && s != "y" && s != "z")
      item.fail("expected a file axis x, y, z, -x, -y or -z in the axes of " + what + ", found " + item.describe());
    const int from = s[0] - 'x';
    if (used[from]) item.fail("file axis " + s + " appears twice in the axes of " + what + "; expected each of x, y, z once");
    used[from] = true;
    b.from[i] = from;
    b.sign[i] = sign;
  }
}

mocap::PositionBinding read_position(const rig::Rig& rig, const YamlRef& node, const std::string& what) {
  node.expect_only_keys({"joint", "target", "scale", "origin", "axes", "offset"}, what);
  mocap::PositionBinding b;
  b.where = node.where();
  read_source_joint(node, what, b.joint, b.joint_where);
  const YamlRef target = node.at("target", what + " (an effector of the rig's kinematics)");
  b.target = target.as_string("the target of " + what);
  if (!rig.kinematics)
    target.fail("target '" + b.target + "' needs inverse kinematics, but rig '" + rig.name +
                "' has no kinematics section; expected a rig with joints and effectors");
  if (!rig.kinematics->model.find_effector(b.target)) {
    std::string names;
    for (const kinematics::Effector& e : rig.kinematics->model.effectors()) names += (names.empty() ? "" : ", ") + e.name;
    target.fail("unknown effector '" + b.target +
                "'; expected one of the rig's effectors: " + (names.empty() ? "(none)" : names));
  }
  b.scale = retarget_number(node, "scale", "the scale of " + what, 1);
  if (!(b.scale > 0))
    node.at("scale", what).fail("expected the scale of " + what + " above 0, found " + node.at("scale", what).describe());
  if (auto origin = node.find("origin")) {
    b.origin = origin->as_string("the origin joint of " + what);
    b.origin_where = origin->where();
  }
  if (auto axes = node.find("axes")) read_axes(*axes, what, b);
  if (auto offset = node.find("offset")) {
    if (!offset->is_sequence() || offset->size() != 3)
      offset->fail("expected the offset of " + what + " as [x, y, z] in metres, found " + offset->describe());
    for (std::size_t i = 0; i < 3; ++i) b.offset[static_cast<Eigen::Index>(i)] = (*offset)[i].as_double("the offset of " + what);
  }
  return b;
}

}  // namespace

mocap::RetargetMap load_retarget_map(const std::string& path, const rig::Rig& rig) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  root.expect_only_keys({"retarget"}, "a retarget map");
  const YamlRef section = root.at("retarget", "a retarget map");
  section.expect_only_keys({"source_units", "rotations", "positions"}, "retarget");
  mocap::RetargetMap map;
  map.file = path;
  if (auto units = section.find("source_units")) {
    map.source_units = units->as_double("source_units (metres per file unit)");
    if (!(map.source_units > 0)) units->fail("expected source_units (metres per file unit) above 0, found " + units->describe());
  }
  std::map<std::string, SourceLocation> bound;  // channel or target name -> where it was bound first
  const auto bind_once = [&bound](const std::string& key, const std::string& name, const SourceLocation& where) {
    const auto [it, fresh] = bound.emplace(key, where);
    if (!fresh)
      throw InputError(where, name + " is already driven by the binding at line " + std::to_string(it->second.line) +
                                  "; expected each channel and target driven once");
  };
  if (auto rotations = section.find("rotations")) {
    rotations->expect_sequence("the rotations of retarget");
    for (std::size_t i = 0; i < rotations->size(); ++i) {
      map.rotations.push_back(read_rotation(rig, (*rotations)[i], "rotation " + std::to_string(i + 1)));
      bind_once("channel " + map.rotations.back().channel, "channel '" + map.rotations.back().channel + "'",
                (*rotations)[i].at("channel", "").where());
    }
  }
  if (auto positions = section.find("positions")) {
    positions->expect_sequence("the positions of retarget");
    for (std::size_t i = 0; i < positions->size(); ++i) {
      map.positions.push_back(read_position(rig, (*positions)[i], "position " + std::to_string(i + 1)));
      const mocap::PositionBinding& b = map.positions.back();
      bind_once("target " + b.target, "target '" + b.target + "'", (*positions)[i].at("target", "").where());
      // The joints that move the effector drive their channels: no rotation may drive them too.
      const auto effector = *rig.kinematics->model.find_effector(b.target);
      for (const std::size_t k : rig::bindings_moving(*rig.kinematics, effector)) {
        const std::string& channel = rig.channels[rig.kinematics->bindings[k].channel].name;
        for (std::size_t r = 0; r < map.rotations.size(); ++r)
          if (map.rotations[r].channel == channel)
            throw InputError((*(section.find("rotations")))[r].at("channel", "").where(),
                             "channel '" + channel + "' is moved by target '" + b.target + "' (inverse kinematics, line " +
                                 std::to_string(b.where.line) + ") and also by this rotation; expected one or the other");
      }
    }
  }
  if (map.rotations.empty() && map.positions.empty())
    section.fail("found no bindings; expected rotations: or positions: with at least one entry");
  return map;
}

}  // namespace avar::config
