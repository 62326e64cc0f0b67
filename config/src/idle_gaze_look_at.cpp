#include "idle_gaze_look_at.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "avar/core/format.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/workspace.hpp"

namespace avar::config {
namespace {

bool gaze_look_at_angular_unit(const std::string& unit) {
  return unit == "deg" || unit == "°" || unit == "degree" || unit == "degrees" || unit == "rad" || unit == "radian" ||
         unit == "radians";
}

/// The tighter of two limits where 0 (or less) means none.
double gaze_look_at_tighter(double a, double b) {
  if (a <= 0) return b;
  if (b <= 0) return a;
  return std::min(a, b);
}

/// The binding (index into kinematics.bindings) of the joint a channel drives, if any.
std::optional<std::size_t> gaze_look_at_binding_of(const rig::RigKinematics& kin, std::size_t channel) {
  for (std::size_t b = 0; b < kin.bindings.size(); ++b)
    if (kin.bindings[b].channel == channel) return b;
  return std::nullopt;
}

std::optional<std::size_t> gaze_look_at_joint_of(const kinematics::Model& model, std::size_t q_index) {
  for (std::size_t j = 0; j < model.joint_count(); ++j)
    if (model.joint(j).q_index == q_index) return j;
  return std::nullopt;
}

double gaze_look_at_positive(const YamlRef& node, const std::string& what) {
  const double v = node.as_double(what);
  if (!(v > 0)) node.fail("expected " + what + " above 0, found " + node.describe());
  return v;
}

}  // namespace

void read_gaze_look_at(const rig::Rig& rig, const YamlRef& node, playback::GazeSpec& gaze, std::vector<const char*>& owner) {
  const YamlRef look = node.at("look_at", "the gaze");
  look.expect_map("look_at ({effectors: [EYE, ...], aim: [x, y, z]})");
  look.expect_only_keys({"effectors", "aim"}, "look_at");
  if (!rig.kinematics)
    look.fail("look-at gaze aims the eyes through the rig's kinematics; expected a kinematics section in the rig");
  const rig::RigKinematics& kin = *rig.kinematics;
  const kinematics::Model& model = kin.model;
  playback::GazeLookAt out;

  // The eyes, and their line of sight.
  const YamlRef eyes = look.at("effectors", "look_at");
  eyes.expect_sequence("effectors (the eyes: effectors of the rig's kinematics)");
  if (eyes.size() == 0) eyes.fail("expected at least one eye effector");
  std::string names;
  for (const kinematics::Effector& e : model.effectors()) names += (names.empty() ? "" : ", ") + e.name;
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    const std::string name = eyes[i].as_string("an eye effector");
    const auto e = model.find_effector(name);
    if (!e) eyes[i].fail("expected an effector of the rig's kinematics, found '" + name + "'; the effectors are: " + names);
    if (std::find(out.effectors.begin(), out.effectors.end(), *e) != out.effectors.end())
      eyes[i].fail("eye effector '" + name + "' is named twice");
    out.effectors.push_back(*e);
  }
  if (auto aim = look.find("aim")) {
    aim->expect_sequence("aim ([x, y, z]: the eyes' line of sight in their effector frame)");
    if (aim->size() != 3) aim->fail("expected aim to be [x, y, z], found " + std::to_string(aim->size()) + " numbers");
    for (std::size_t a = 0; a < 3; ++a) out.aim_axis[a] = (*aim)[a].as_double("a component of aim");
    if (std::hypot(out.aim_axis[0], out.aim_axis[1], out.aim_axis[2]) == 0) aim->fail("expected aim to be a non-zero direction");
  }

  // The head: its joints are the ones its channels drive; the eyes hang from the lowest of them.
  const auto is_head_joint = [&](std::size_t j) {
    if (!model.joint(j).movable()) return false;
    const std::size_t c = kin.bindings[model.joint(j).q_index].channel;
    return (gaze.head_pan && c == *gaze.head_pan) || (gaze.head_tilt && c == *gaze.head_tilt);
  };
  for (std::size_t i = 0; i < out.effectors.size(); ++i) {
    std::size_t j = model.effector(out.effectors[i]).joint;
    while (j != kinematics::Joint::kNoParent && !is_head_joint(j)) j = model.joint(j).parent;
    if (i == 0) out.mount_joint = j;
    else if (j != out.mount_joint)
      eyes[i].fail("expected every eye to hang from the same head joint; '" + model.effector(out.effectors[i]).name +
                   "' does not hang from the first eye's");
  }

  // The eyes' own joints: below the head, revolute, on deg or rad channels only gaze drives.
  std::vector<std::size_t> own_joints;
  for (std::size_t i = 0; i < out.effectors.size(); ++i) {
    const std::string eye = model.effector(out.effectors[i]).name;
    bool moves = false;
    for (std::size_t j = model.effector(out.effectors[i]).joint; j != out.mount_joint; j = model.joint(j).parent) {
      const kinematics::Joint& joint = model.joint(j);
      if (!joint.movable()) continue;
      moves = true;
      const std::size_t c = kin.bindings[joint.q_index].channel;
      const rig::ChannelSpec& ch = rig.channels[c];
      if (joint.type != kinematics::JointType::revolute)
        eyes[i].fail("eye '" + eye + "' is moved by joint '" + joint.name +
                     "', which slides; look-at gaze turns eyes on revolute joints");
      if (!gaze_look_at_angular_unit(ch.unit))
        eyes[i].fail("eye '" + eye + "' is turned by channel '" + ch.name + "' in '" + ch.unit +
                     "'; look-at gaze needs the eye channels in deg or rad");
      if (owner[c] && owner[c] != std::string_view("gaze"))
        eyes[i].fail("channel '" + ch.name + "' is already driven by idle " + owner[c] + "; gaze needs a channel of its own");
      owner[c] = "gaze";
      if (std::find(own_joints.begin(), own_joints.end(), j) == own_joints.end()) {
        own_joints.push_back(j);
        out.eye_channels.push_back(c);
      }
    }
    if (!moves) eyes[i].fail("eye '" + eye + "' has no joint of its own below the head's: nothing would aim it");
  }

  // The rest pose: the gaze frame, the eyes' spacing and the parallax of a near target.
  std::vector<double> q(model.dof(), 0.0);
  for (const rig::JointBinding& b : kin.bindings)
    q[b.q_index] =
        std::clamp(b.to_joint(rig.channels[b.channel].rest), model.lower_limits()[b.q_index], model.upper_limits()[b.q_index]);
  kinematics::Workspace ws(model);
  (void)kinematics::forward_kinematics(model, q, ws);
  const Eigen::Vector3d axis = Eigen::Vector3d(out.aim_axis[0], out.aim_axis[1], out.aim_axis[2]).normalized();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), ahead = Eigen::Vector3d::Zero();
  for (const std::size_t e : out.effectors) {
    const Eigen::Isometry3d pose = kinematics::effector_pose(model, ws, e);
    centre += pose.translation() / static_cast<double>(out.effectors.size());
    ahead += pose.linear() * axis / static_cast<double>(out.effectors.size());
  }
  if (ahead.norm() < 0.5) look.fail("expected the eyes to look the same way at rest (their channels' rest values)");
  ahead.normalize();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ() - ahead.z() * ahead;
  if (up.norm() < 0.3) look.fail("expected the eyes to look ahead at rest, not up or down (the kinematics' z is up)");
  up.normalize();
  const Eigen::Vector3d left = up.cross(ahead);
  for (std::size_t a = 0; a < 3; ++a) {
    const auto k = static_cast<Eigen::Index>(a);
    out.centre[a] = centre[k];
    out.ahead[a] = ahead[k];
    out.left[a] = left[k];
    out.up[a] = up[k];
  }
  for (const std::size_t e : out.effectors)
    out.half_interocular_m =
        std::max(out.half_interocular_m, (kinematics::effector_pose(model, ws, e).translation() - centre).norm());
  double reach = 0;  // the farthest an eye joint sits from the centre
  for (const std::size_t j : own_joints) reach = std::max(reach, (ws.joint_pose(j).translation() - centre).norm());

  if (auto distance = node.find("distance")) {
    distance->expect_map("distance ({far: M, near: M, near_probability: P})");
    distance->expect_only_keys({"far", "near", "near_probability"}, "distance");
    if (auto f = distance->find("far")) out.far_m = gaze_look_at_positive(*f, "the far distance (m)");
    if (auto n = distance->find("near")) out.near_m = gaze_look_at_positive(*n, "the near distance (m)");
    if (out.near_m > out.far_m) distance->fail("expected the near distance at most the far one");
    if (auto p = distance->find("near_probability")) {
      gaze.near_probability = p->as_double("near_probability");
      if (gaze.near_probability < 0 || gaze.near_probability > 1)
        p->fail("expected near_probability from 0 to 1, found " + p->describe());
    }
  }
  if (out.near_m < 2 * reach)
    (node.find("distance") ? *node.find("distance") : look)
        .fail("expected the near distance at least " + format_number(2 * reach) +
              " m (twice the farthest eye joint from the eyes' centre), found " + format_number(out.near_m));

  // The eyes' limits in degrees of gaze: a near target's sight lines turn faster than its
  // direction from the centre by up to near / (near - reach).
  const double gain = out.near_m / (out.near_m - reach);
  playback::IdleChannelLimits& l = out.eye_limits;
  l.max_velocity = l.max_acceleration = l.max_jerk = 0;
  for (const std::size_t j : own_joints) {
    const rig::JointBinding& b = kin.bindings[model.joint(j).q_index];
    const rig::ChannelSpec& ch = rig.channels[b.channel];
    const double degrees = std::abs(b.scale) * 180 / std::numbers::pi / gain;  // per channel unit
    l.max_velocity = gaze_look_at_tighter(l.max_velocity, ch.max_velocity * degrees);
    l.max_acceleration = gaze_look_at_tighter(l.max_acceleration, ch.max_acceleration * degrees);
    l.max_jerk = gaze_look_at_tighter(l.max_jerk, ch.max_jerk * degrees);
  }

  // The head turns its share of the gaze's angle through its joint: channel units per degree,
  // signed so that a positive pan turns it left and a positive tilt up.
  const YamlRef head = node.find("head") ? *node.find("head") : node;
  const std::array<std::optional<std::size_t>, 2> head_channels{gaze.head_pan, gaze.head_tilt};
  const std::array<const char*, 2> head_keys{"pan", "tilt"};
  const std::array<Eigen::Vector3d, 2> turns{up, -left};
  for (std::size_t a = 0; a < 2; ++a) {
    if (!head_channels[a]) continue;
    const YamlRef where = head.find(head_keys[a]) ? *head.find(head_keys[a]) : head;
    const rig::ChannelSpec& ch = rig.channels[*head_channels[a]];
    const auto b = gaze_look_at_binding_of(kin, *head_channels[a]);
    if (!b) where.fail("look-at gaze turns the head through the kinematics; channel '" + ch.name + "' drives no joint of it");
    const auto j = gaze_look_at_joint_of(model, kin.bindings[*b].q_index);
    if (!j || model.joint(*j).type != kinematics::JointType::revolute)
      where.fail("look-at gaze turns the head; channel '" + ch.name + "' drives a joint that slides");
    const double along = (ws.joint_pose(*j).linear() * model.joint(*j).axis).dot(turns[a]);
    if (std::abs(along) < 0.7)
      where.fail(std::string("expected the head's ") + head_keys[a] + " joint to turn about the " +
                 (a == 0 ? "vertical (the kinematics' z)" : "eyes' left-right axis") + " at rest; '" + model.joint(*j).name +
                 "' does not");
    out.head_units_per_degree[a] = (along > 0 ? 1.0 : -1.0) * std::numbers::pi / 180 / kin.bindings[*b].scale;
  }

  if (gaze.tilt_min < -80 || gaze.tilt_max > 80 || gaze.pan_min < -170 || gaze.pan_max > 170)
    (node.find("field") ? *node.find("field") : node)
        .fail("expected the look-at gaze field within pan [-170, 170] and tilt [-80, 80] degrees");
  gaze.look_at = std::move(out);
}

}  // namespace avar::config
