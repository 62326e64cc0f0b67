#include "rig_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "avar/core/format.hpp"
#include "avar/kinematics/denavit_hartenberg.hpp"
#include "avar/kinematics/model_builder.hpp"
#include "avar/kinematics/urdf_import.hpp"
#include "avar/kinematics/urdf_visuals.hpp"
#include "yaml_vectors.hpp"

namespace avar::config {
namespace {

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

/// Reads how a movable joint is driven: {channel, scale, offset} from `node`, the scale from the
/// channel's unit when not given. Returns the binding (q_index left for the caller).
rig::JointBinding read_binding(const rig::Rig& rig, const YamlRef& node, const std::string& what, kinematics::JointType type) {
  rig::JointBinding binding;
  const YamlRef channel = node.at("channel", what + " (the channel that drives it)");
  const std::string channel_name = channel.as_string("the channel of " + what);
  const auto ci = rig.find_channel(channel_name);
  if (!ci) channel.fail("unknown channel '" + channel_name + "'; expected one of the rig's channels: " + rig.channel_names());
  const rig::ChannelSpec& ch = rig.channels[*ci];
  binding.channel = *ci;
  const bool revolute = type == kinematics::JointType::revolute;
  if (auto scale = node.find("scale")) {
    binding.scale = scale->as_double("the scale of " + what);
    if (binding.scale == 0) scale->fail("expected the scale of " + what + " to be non-zero (joint units per channel unit)");
  } else if (auto s = scale_for_unit(ch.unit, type)) {
    binding.scale = *s;
  } else {
    channel.fail("channel '" + channel_name + "' is in '" + ch.unit + "', which " + what + " cannot convert; expected the channel's unit to be " +
                 (revolute ? "deg or rad" : "m, cm or mm") + ", or a scale (joint " + (revolute ? "radians" : "metres") +
                 " per channel unit)");
  }
  if (auto offset = node.find("offset")) binding.offset = offset->as_double("the offset of " + what);
  return binding;
}

/// The channel's range as joint limits.
std::pair<double, double> channel_limits(const rig::Rig& rig, const rig::JointBinding& b) {
  const rig::ChannelSpec& ch = rig.channels[b.channel];
  const double lo = b.to_joint(ch.min), hi = b.to_joint(ch.max);
  return {std::min(lo, hi), std::max(lo, hi)};
}

/// A model imported from URDF or DH, bound to channels by `joints: {joint: {channel, scale,
/// offset}}`; every movable joint needs a channel, and its limits become the intersection of its
/// own and its channel's, so the solver never asks for what the channel cannot do.
rig::RigKinematics bind_imported(const rig::Rig& rig, const kinematics::Model& imported, const YamlRef& joints,
                                 const YamlRef& section) {
  joints.expect_map("joints (a map of joint name to {channel, scale, offset})");
  std::string names;
  for (const kinematics::Joint& j : imported.joints())
    if (j.movable()) names += (names.empty() ? "" : ", ") + j.name;
  for (auto it = joints.node.begin(); it != joints.node.end(); ++it) {
    const YamlRef name{it->first, joints.file};
    const auto j = imported.find_joint(name.as_string("a joint name"));
    if (!j || !imported.joint(*j).movable())
      name.fail("unknown movable joint '" + name.node.Scalar() + "'; expected one of: " + names);
  }
  kinematics::ModelBuilder builder;
  std::vector<rig::JointBinding> bindings;
  for (const kinematics::Joint& j : imported.joints()) {
    kinematics::JointSpec spec{j.name, j.type, j.on_base() ? std::string() : imported.joint(j.parent).name, j.origin, j.axis,
                               j.lower, j.upper};
    if (j.movable()) {
      const std::string what = "joint '" + j.name + "'";
      const auto entry = joints.find(j.name);
      if (!entry) joints.fail(what + " has no channel; expected " + j.name + ": {channel: ...} among the joints");
      entry->expect_only_keys({"channel", "scale", "offset"}, what);
      rig::JointBinding b = read_binding(rig, *entry, what, j.type);
      const auto [lo, hi] = channel_limits(rig, b);
      spec.lower = std::max(j.lower, lo);
      spec.upper = std::min(j.upper, hi);
      if (spec.lower > spec.upper)
        entry->fail("the limits of " + what + " [" + format_number(j.lower) + ", " + format_number(j.upper) +
                    "] and of its channel [" + format_number(lo) + ", " + format_number(hi) + "] do not overlap");
      b.q_index = bindings.size();
      bindings.push_back(b);
    }
    builder.add_joint(spec, j.where);
  }
  for (const kinematics::Effector& e : imported.effectors())
    builder.add_effector({e.name, imported.joint(e.joint).name, e.tool}, e.where);
  return rig::RigKinematics{builder.build(), std::move(bindings), section.where(), {}};
}

/// dh: {convention: standard | modified, rows: [{a, alpha, d, theta}], tool: {xyz, rpy}}
kinematics::Model read_dh(const YamlRef& node) {
  node.expect_map("the DH chain ({convention, rows, tool})");
  node.expect_only_keys({"convention", "rows", "tool"}, "the DH chain");
  bool modified = false;
  if (auto c = node.find("convention")) {
    const std::string name = c->as_string("the DH convention");
    if (name == "modified") modified = true;
    else if (name != "standard") c->fail("unknown DH convention " + c->describe() + "; expected one of: standard, modified");
  }
  const YamlRef rows = node.at("rows", "the DH chain");
  rows.expect_sequence("the DH rows ([{a, alpha, d, theta}, ...], metres and radians)");
  if (rows.size() == 0) rows.fail("expected at least one DH row");
  std::vector<kinematics::DhRow> dh;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const YamlRef r = rows[i];
    const std::string what = "DH row " + std::to_string(i + 1);
    r.expect_only_keys({"a", "alpha", "d", "theta"}, what);
    kinematics::DhRow row;
    const auto get = [&](const char* key) { return r.find(key) ? r.at(key, what).as_double(std::string(key) + " of " + what) : 0.0; };
    row.a = get("a");
    row.alpha = get("alpha");
    row.d = get("d");
    row.theta = get("theta");
    // Revolute DH joints turn all the way; the channels bound to them set the real limits.
    row.lower = -2 * std::numbers::pi;
    row.upper = 2 * std::numbers::pi;
    row.where = r.where();
    dh.push_back(row);
  }
  const Eigen::Isometry3d tool = read_origin(node.find("tool"), "the tool of the DH chain");
  return modified ? kinematics::chain_from_modified_dh(dh, tool) : kinematics::chain_from_standard_dh(dh, tool);
}

}  // namespace

rig::RigKinematics read_rig_kinematics(const rig::Rig& rig, const YamlRef& node) {
  node.expect_map("the kinematics section ({joints: ..., effectors: ...}, or urdf: FILE / dh: {...} with joints)");
  node.expect_only_keys({"joints", "effectors", "urdf", "dh"}, "the kinematics section");
  if (node.find("urdf") && node.find("dh")) node.fail("the kinematics section names both urdf and dh; expected one geometry");
  if (auto urdf = node.find("urdf")) {
    if (node.find("effectors")) node.at("effectors", "").fail("a URDF's effectors are its links; expected no effectors section");
    // A relative path is relative to the rig file.
    std::filesystem::path path = urdf->as_string("the URDF file");
    if (path.is_relative()) path = std::filesystem::path(*node.file).parent_path() / path;
    rig::RigKinematics imported =
        bind_imported(rig, kinematics::model_from_urdf_file(path.string()), node.at("joints", "the kinematics section"), node);
    imported.visuals = kinematics::visuals_from_urdf_file(path.string());
    return imported;
  }
  if (auto dh = node.find("dh")) {
    if (node.find("effectors")) node.at("effectors", "").fail("a DH chain's effector is its tip; expected no effectors section");
    return bind_imported(rig, read_dh(*dh), node.at("joints", "the kinematics section (joint1..jointN: {channel})"), node);
  }
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
  std::vector<rig::JointBinding> bindings;
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
    rig::JointBinding binding;
    if (movable) {
      spec.axis = read_vector(j.node.at("axis", what), "the axis of " + what);
      binding = read_binding(rig, j.node, what, spec.type);
      // The joint's limits are its channel's: IK never asks for what the channel cannot do.
      std::tie(spec.lower, spec.upper) = channel_limits(rig, binding);
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
  return rig::RigKinematics{builder.build(), std::move(bindings), node.where(), {}};
}

}  // namespace avar::config
