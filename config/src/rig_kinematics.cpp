#include "avar/config/rig_kinematics.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "avar/core/format.hpp"
#include "avar/kinematics/model_builder.hpp"

namespace avar::config {
namespace {

Eigen::Vector3d read_vector(const YamlRef& node, const std::string& what) {
  node.expect_sequence(what + " ([x, y, z])");
  if (node.size() != 3) node.fail("expected " + what + " to have 3 numbers [x, y, z], found " + std::to_string(node.size()));
  return {node[0].as_double(what + " x"), node[1].as_double(what + " y"), node[2].as_double(what + " z")};
}

/// origin: {xyz: [m, m, m], rpy: [rad, rad, rad]} (roll about x, then pitch about y, then yaw
/// about z, in the parent frame, as URDF), both optional.
Eigen::Isometry3d read_origin(const std::optional<YamlRef>& node, const std::string& what) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  if (!node) return t;
  node->expect_map(what + " ({xyz: [x, y, z], rpy: [roll, pitch, yaw]})");
  node->expect_only_keys({"xyz", "rpy"}, what);
  if (auto xyz = node->find("xyz")) t.translation() = read_vector(*xyz, "the xyz of " + what + " (m)");
  if (auto rpy = node->find("rpy")) {
    const Eigen::Vector3d a = read_vector(*rpy, "the rpy of " + what + " (rad)");
    t.linear() = (Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
  }
  return t;
}

/// Joint units (rad or m) per channel unit, from the channel's unit where it says.
std::optional<double> scale_for_unit(const std::string& unit, kinematics::JointType type) {
  if (type == kinematics::JointType::revolute) {
    if (unit == "deg" || unit == "degree" || unit == "degrees" || unit == "°") return std::numbers::pi / 180;
    if (unit == "rad" || unit == "radian" || unit == "radians") return 1.0;
  } else {
    if (unit == "m") return 1.0;
    if (unit == "cm") return 0.01;
    if (unit == "mm") return 0.001;
  }
  return std::nullopt;
}

struct PendingJoint {
  std::string name;
  YamlRef node;
};

}  // namespace

control::RigKinematics read_rig_kinematics(const control::Rig& rig, const YamlRef& node) {
  node.expect_map("the kinematics section ({joints: ..., effectors: ...})");
  node.expect_only_keys({"joints", "effectors"}, "the kinematics section");
  const YamlRef joints = node.at("joints", "the kinematics section");
  joints.expect_map("joints (a map of joint name to its type, parent, axis, origin and channel)");
  if (joints.size() == 0) joints.fail("expected at least one joint");

  // Joints may be listed in any order: add each after its parent, and find cycles on the way.
  std::map<std::string, PendingJoint> pending;
  std::vector<std::string> order_in_file;
  for (auto it = joints.node.begin(); it != joints.node.end(); ++it) {
    const std::string name = it->first.Scalar();
    if (pending.count(name)) YamlRef{it->first, joints.file}.fail("joint '" + name + "' is defined twice");
    pending.emplace(name, PendingJoint{name, YamlRef{it->second, joints.file}});
    order_in_file.push_back(name);
  }
  auto parent_of = [&](const PendingJoint& j) -> std::string {
    auto p = j.node.find("parent");
    return p ? p->as_string("the parent of joint '" + j.name + "'") : "";
  };
  std::vector<std::string> order;
  std::map<std::string, int> state;  // 0 new, 1 on the current path, 2 placed
  std::vector<std::string> path;
  std::function<void(const std::string&)> place = [&](const std::string& name) {
    const PendingJoint& j = pending.at(name);
    if (state[name] == 2) return;
    if (state[name] == 1) {
      std::string loop;
      bool in = false;
      for (const std::string& p : path) {
        in = in || p == name;
        if (in) loop += p + " -> ";
      }
      j.node.at("parent", "").fail("joint '" + name + "' is its own ancestor (" + loop + name +
                                   "); expected a tree: every chain of parents ends at the base");
    }
    state[name] = 1;
    path.push_back(name);
    const std::string parent = parent_of(j);
    if (!parent.empty()) {
      if (!pending.count(parent)) {
        std::string names;
        for (const std::string& n : order_in_file) names += (names.empty() ? "" : ", ") + n;
        j.node.at("parent", "").fail("unknown parent joint '" + parent + "' of joint '" + name +
                                     "'; expected one of: " + names + " (or no parent: the base)");
      }
      place(parent);
    }
    path.pop_back();
    state[name] = 2;
    order.push_back(name);
  };
  for (const std::string& name : order_in_file) place(name);

  kinematics::ModelBuilder builder;
  std::vector<control::JointBinding> bindings;
  for (const std::string& name : order) {
    const PendingJoint& j = pending.at(name);
    const std::string what = "joint '" + name + "'";
    j.node.expect_map(what + " ({type, parent, axis, origin, channel})");
    j.node.expect_only_keys({"type", "parent", "axis", "origin", "channel", "scale", "offset"}, what);
    kinematics::JointSpec spec;
    spec.name = name;
    spec.parent = parent_of(j);
    if (auto type = j.node.find("type")) {
      const std::string t = type->as_string("the type of " + what);
      if (t == "revolute") spec.type = kinematics::JointType::revolute;
      else if (t == "prismatic") spec.type = kinematics::JointType::prismatic;
      else if (t == "fixed") spec.type = kinematics::JointType::fixed;
      else type->fail("unknown joint type " + type->describe() + " of " + what + "; expected one of: revolute, prismatic, fixed");
    }
    spec.origin = read_origin(j.node.find("origin"), "the origin of " + what);
    const bool movable = spec.type != kinematics::JointType::fixed;
    control::JointBinding binding;
    if (movable) {
      spec.axis = read_vector(j.node.at("axis", what), "the axis of " + what);
      const YamlRef channel = j.node.at("channel", what + " (the channel that drives it)");
      const std::string channel_name = channel.as_string("the channel of " + what);
      const auto ci = rig.find_channel(channel_name);
      if (!ci) channel.fail("unknown channel '" + channel_name + "'; expected one of the rig's channels: " + rig.channel_names());
      const control::ChannelSpec& ch = rig.channels[*ci];
      binding.channel = *ci;
      if (auto scale = j.node.find("scale")) {
        binding.scale = scale->as_double("the scale of " + what);
        if (binding.scale == 0) scale->fail("expected the scale of " + what + " to be non-zero (joint units per channel unit)");
      } else if (auto s = scale_for_unit(ch.unit, spec.type)) {
        binding.scale = *s;
      } else {
        channel.fail("channel '" + channel_name + "' is in '" + ch.unit + "', which " + what +
                     " cannot convert; expected the channel's unit to be " +
                     (spec.type == kinematics::JointType::revolute ? "deg or rad" : "m, cm or mm") +
                     ", or a scale (joint " + (spec.type == kinematics::JointType::revolute ? "radians" : "metres") +
                     " per channel unit)");
      }
      if (auto offset = j.node.find("offset")) binding.offset = offset->as_double("the offset of " + what);
      // The joint's limits are its channel's: IK never asks for what the channel cannot do.
      const double a = binding.to_joint(ch.min), b = binding.to_joint(ch.max);
      spec.lower = std::min(a, b);
      spec.upper = std::max(a, b);
    } else {
      for (const char* key : {"axis", "channel", "scale", "offset"})
        if (auto extra = j.node.find(key)) extra->fail(std::string(key) + " does not apply to the fixed " + what);
    }
    builder.add_joint(spec, j.node.where());
    if (movable) {
      binding.q_index = bindings.size();
      bindings.push_back(binding);
    }
  }

  if (auto effectors = node.find("effectors")) {
    effectors->expect_map("effectors (a map of effector name to its joint and origin)");
    for (auto it = effectors->node.begin(); it != effectors->node.end(); ++it) {
      const std::string name = it->first.Scalar();
      const YamlRef e{it->second, node.file};
      const std::string what = "effector '" + name + "'";
      e.expect_map(what + " ({joint, origin})");
      e.expect_only_keys({"joint", "origin"}, what);
      kinematics::EffectorSpec spec;
      spec.name = name;
      const YamlRef joint = e.at("joint", what);
      spec.joint = joint.as_string("the joint of " + what);
      if (!pending.count(spec.joint)) {
        std::string names;
        for (const std::string& n : order_in_file) names += (names.empty() ? "" : ", ") + n;
        joint.fail("unknown joint '" + spec.joint + "' for " + what + "; expected one of: " + names);
      }
      spec.tool = read_origin(e.find("origin"), "the origin of " + what);
      builder.add_effector(spec, e.where());
    }
  }
  return control::RigKinematics{builder.build(), std::move(bindings), node.where()};
}

}  // namespace avar::config
