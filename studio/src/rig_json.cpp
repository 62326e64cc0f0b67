#include "rig_json.hpp"

#include <Eigen/Geometry>
#include <cctype>
#include <filesystem>
#include <optional>

#include "avar/playback/runtime/keys.hpp"

namespace avar::studio {
namespace {

using nlohmann::json;

/// A rigid transform as `{xyz: [m], quaternion: [w, x, y, z]}`.
json transform_json(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.rotation());
  const Eigen::Vector3d p = t.translation();
  return {{"xyz", {p.x(), p.y(), p.z()}}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

const char* joint_type_name(kinematics::JointType type) {
  switch (type) {
    case kinematics::JointType::revolute: return "revolute";
    case kinematics::JointType::prismatic: return "prismatic";
    case kinematics::JointType::fixed: return "fixed";
  }
  return "fixed";
}

const char* shape_name(kinematics::VisualShape shape) {
  switch (shape) {
    case kinematics::VisualShape::box: return "box";
    case kinematics::VisualShape::cylinder: return "cylinder";
    case kinematics::VisualShape::sphere: return "sphere";
    case kinematics::VisualShape::mesh: return "mesh";
  }
  return "box";
}

/// A visual's shape: box {size: [x, y, z]}, cylinder {radius, length} (along its frame's z),
/// sphere {radius}, or mesh {url, format, file, found, scale}; metres.
json visual_json(const rig::RigKinematics& k, std::size_t index) {
  const kinematics::LinkVisual& v = k.visuals[index];
  const std::optional<std::size_t> joint = v.joint.empty() ? std::nullopt : k.model.find_joint(v.joint);
  json out = {{"link", v.link},
              {"joint", joint ? json(*joint) : json(nullptr)},
              {"origin", transform_json(v.origin)},
              {"shape", shape_name(v.shape)},
              {"color", v.rgba ? json(*v.rgba) : json(nullptr)}};
  switch (v.shape) {
    case kinematics::VisualShape::box: out["size"] = {v.size.x(), v.size.y(), v.size.z()}; break;
    case kinematics::VisualShape::cylinder:
      out["radius"] = v.size.x();
      out["length"] = v.size.y();
      break;
    case kinematics::VisualShape::sphere: out["radius"] = v.size.x(); break;
    case kinematics::VisualShape::mesh: {
      std::error_code ignored;
      out["url"] = "/api/mesh/" + std::to_string(index);
      out["format"] = mesh_format(v.mesh_path);
      out["file"] = v.mesh;
      out["found"] = std::filesystem::is_regular_file(v.mesh_path, ignored);
      out["scale"] = {v.scale.x(), v.scale.y(), v.scale.z()};
      break;
    }
  }
  return out;
}

/// The joint tree in topological order (a parent before its children). A movable joint names the
/// channel that drives it: joint value (rad or m) = (channel value - offset) * scale.
json kinematics_json(const rig::Rig& rig) {
  if (!rig.kinematics) return nullptr;
  const kinematics::Model& model = rig.kinematics->model;
  json joints = json::array();
  for (const kinematics::Joint& j : model.joints()) {
    json joint = {{"name", j.name},
                  {"type", joint_type_name(j.type)},
                  {"parent", j.on_base() ? json(nullptr) : json(j.parent)},
                  {"origin", transform_json(j.origin)},
                  {"axis", {j.axis.x(), j.axis.y(), j.axis.z()}},
                  {"channel", nullptr}};
    for (const rig::JointBinding& b : rig.kinematics->bindings)
      if (j.movable() && b.q_index == j.q_index) {
        joint["channel"] = rig.channels[b.channel].name;
        joint["scale"] = b.scale;
        joint["offset"] = b.offset;
      }
    joints.push_back(std::move(joint));
  }
  json effectors = json::array();
  for (const kinematics::Effector& e : model.effectors())
    effectors.push_back({{"name", e.name}, {"joint", e.joint}, {"origin", transform_json(e.tool)}});
  json visuals = json::array();
  for (std::size_t v = 0; v < rig.kinematics->visuals.size(); ++v) visuals.push_back(visual_json(*rig.kinematics, v));
  return {{"joints", joints}, {"effectors", effectors}, {"visuals", visuals}};
}

}  // namespace

std::string mesh_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".stl" || ext == ".dae" || ext == ".obj") return ext.substr(1);
  return "unknown";
}

json rig_json(const rig::Rig& rig) {
  json channels = json::array();
  for (const rig::ChannelSpec& c : rig.channels)
    channels.push_back({{"name", c.name},
                        {"unit", c.unit},
                        {"kind", c.digital() ? "digital" : "analog"},
                        {"min", c.min},
                        {"max", c.max},
                        {"rest", c.rest},
                        {"max_velocity", maybe(c.max_velocity)},
                        {"max_acceleration", maybe(c.max_acceleration)},
                        {"max_jerk", maybe(c.max_jerk)}});
  json links = json::array();
  for (const rig::LinkSpec& l : rig.links) links.push_back({{"name", l.name}, {"protocol", l.protocol}, {"port", l.port}});
  return {{"name", rig.name},
          {"rate_hz", rig.rate_hz},
          {"channels", channels},
          {"links", links},
          {"kinematics", kinematics_json(rig)}};
}

json curve_vocabulary_json() {
  return {{"interpolations", playback::interpolation_name_list()},
          {"easings", playback::easing_name_list()},
          {"handle_types", playback::handle_type_name_list()},
          {"extrapolations", playback::extrapolation_name_list()}};
}

}  // namespace avar::studio
