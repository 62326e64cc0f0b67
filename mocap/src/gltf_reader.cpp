#include "avar/mocap/gltf_reader.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string_view>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "gltf_accessor.hpp"
#include "gltf_sampler.hpp"

namespace avar::mocap {
namespace {

using gltf::Interpolation;
using gltf::KeyedSampler;

/// More samples than this is refused as a likely mistake (a huge key time or rate).
constexpr double kGltfMaxFrames = 1'000'000;

[[noreturn]] void gltf_fail(const std::string& file, const std::string& path, const std::string& problem) {
  throw InputError({file, 0, 0}, path.empty() ? problem : path + ": " + problem);
}

std::string gltf_indexed(const std::string& array, std::size_t i) { return array + "[" + std::to_string(i) + "]"; }

/// Images are never decoded: the reader only needs nodes, skins and animations.
bool skip_gltf_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

/// A binary glTF starts with the magic "glTF" (whatever the file is called).
bool gltf_is_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 4> magic{};
  in.read(magic.data(), magic.size());
  return in && std::string_view(magic.data(), magic.size()) == "glTF";
}

tinygltf::Model gltf_load_model(const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_gltf_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const bool ok = gltf_is_binary(path) ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                                       : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!ok) {
    std::replace(error.begin(), error.end(), '\n', ' ');
    while (!error.empty() && error.back() == ' ') error.pop_back();
    gltf_fail(path, "", "not a readable glTF 2.0 file: " + (error.empty() ? std::string("unknown error") : error));
  }
  return model;
}

/// Each node's parent (-1 for roots), checking the children lists form a forest.
std::vector<std::ptrdiff_t> gltf_node_parents(const tinygltf::Model& model, const std::string& file) {
  std::vector<std::ptrdiff_t> parents(model.nodes.size(), -1);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const auto& children = model.nodes[n].children;
    for (std::size_t k = 0; k < children.size(); ++k) {
      const std::string path = gltf_indexed(gltf_indexed("nodes", n) + ".children", k);
      const int c = children[k];
      if (c < 0 || static_cast<std::size_t>(c) >= model.nodes.size())
        gltf_fail(file, path,
                  "node " + std::to_string(c) + " out of range (the file has " + std::to_string(model.nodes.size()) + ")");
      if (parents[static_cast<std::size_t>(c)] != -1 || static_cast<std::size_t>(c) == n)
        gltf_fail(file, path, "node " + std::to_string(c) + " already has a parent; expected the nodes to form trees");
      parents[static_cast<std::size_t>(c)] = static_cast<std::ptrdiff_t>(n);
    }
  }
  for (std::size_t n = 0; n < parents.size(); ++n) {  // a cycle never reaches a root
    std::ptrdiff_t at = static_cast<std::ptrdiff_t>(n);
    for (std::size_t steps = 0; at != -1; ++steps) {
      if (steps > parents.size()) gltf_fail(file, gltf_indexed("nodes", n), "lies on a cycle of children; expected trees");
      at = parents[static_cast<std::size_t>(at)];
    }
  }
  return parents;
}

struct GltfTrs {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

/// A node's matrix (column-major, as glTF stores it) split into T * R * S.
GltfTrs gltf_decompose(const std::vector<double>& m, const std::string& file, const std::string& path) {
  if (m.size() != 16) gltf_fail(file, path, std::to_string(m.size()) + " numbers; expected 16");
  const Eigen::Matrix4d matrix = Eigen::Map<const Eigen::Matrix4d>(m.data());
  if (!matrix.allFinite() || (matrix.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    gltf_fail(file, path, "not a finite affine transform; expected a last row of 0 0 0 1");
  GltfTrs trs;
  trs.translation = matrix.block<3, 1>(0, 3);
  const Eigen::Matrix3d linear = matrix.topLeftCorner<3, 3>();
  for (int k = 0; k < 3; ++k) trs.scale[k] = linear.col(k).norm();
  if (trs.scale.minCoeff() < 1e-12) gltf_fail(file, path, "a zero scale; expected an invertible transform");
  if (linear.determinant() < 0) trs.scale.x() = -trs.scale.x();
  const Eigen::Matrix3d rotation = linear * trs.scale.cwiseInverse().asDiagonal();
  if ((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() > 1e-5)
    gltf_fail(file, path, "holds shear; expected translation * rotation * scale");
  trs.rotation = Eigen::Quaterniond(rotation).normalized();
  return trs;
}

GltfTrs gltf_node_trs(const tinygltf::Node& node, const std::string& file, const std::string& path) {
  if (!node.matrix.empty()) return gltf_decompose(node.matrix, file, path + ".matrix");
  GltfTrs trs;
  const auto vector3 = [&](const std::vector<double>& v, Eigen::Vector3d& out, const char* name) {
    if (v.empty()) return;
    if (v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
      gltf_fail(file, path + "." + name, "expected 3 finite numbers");
    out = Eigen::Vector3d(v[0], v[1], v[2]);
  };
  vector3(node.translation, trs.translation, "translation");
  vector3(node.scale, trs.scale, "scale");
  if (!node.rotation.empty()) {
    const auto& r = node.rotation;
    const Eigen::Quaterniond q = r.size() == 4 ? Eigen::Quaterniond(r[3], r[0], r[1], r[2]) : Eigen::Quaterniond(0, 0, 0, 0);
    if (!std::isfinite(q.norm()) || q.norm() < 1e-9)
      gltf_fail(file, path + ".rotation", "expected a unit quaternion of 4 finite numbers (x, y, z, w)");
    trs.rotation = q.normalized();
  }
  return trs;
}

/// One animation channel on a skeleton joint.
struct GltfJointChannel {
  std::size_t joint = 0;
  enum class Path : std::uint8_t { translation, rotation, scale } path = Path::translation;
  KeyedSampler sampler;
};

KeyedSampler gltf_read_sampler(const tinygltf::Model& model, std::size_t a, int index, int components, const std::string& file) {
  const tinygltf::Animation& animation = model.animations[a];
  const std::string at = gltf_indexed(gltf_indexed("animations", a) + ".samplers", static_cast<std::size_t>(index));
  const tinygltf::AnimationSampler& s = animation.samplers[static_cast<std::size_t>(index)];
  KeyedSampler keyed;
  keyed.components = components;
  if (s.interpolation == "LINEAR") keyed.interpolation = Interpolation::linear;
  else if (s.interpolation == "STEP") keyed.interpolation = Interpolation::step;
  else if (s.interpolation == "CUBICSPLINE") keyed.interpolation = Interpolation::cubic_spline;
  else gltf_fail(file, at + ".interpolation", "'" + s.interpolation + "'; expected LINEAR, STEP or CUBICSPLINE");
  keyed.times = gltf::read_accessor(model, s.input, 1, file, at + ".input");
  if (keyed.times.empty()) gltf_fail(file, at + ".input", "no keys; expected at least one");
  for (std::size_t k = 0; k < keyed.times.size(); ++k) {
    if (keyed.times[k] < 0) gltf_fail(file, at + ".input", "key " + std::to_string(k) + " at a negative time");
    if (k > 0 && !(keyed.times[k] > keyed.times[k - 1]))
      gltf_fail(file, at + ".input",
                "key " + std::to_string(k) + " at " + format_number(keyed.times[k]) + " s is not after key " +
                    std::to_string(k - 1) + " (" + format_number(keyed.times[k - 1]) + " s); expected strictly increasing times");
  }
  const std::size_t per_key = keyed.interpolation == Interpolation::cubic_spline ? 3 : 1;
  const std::size_t outputs = gltf::accessor_count(model, s.output, file, at + ".output");
  if (outputs != keyed.times.size() * per_key)
    gltf_fail(file, at + ".output",
              std::to_string(outputs) + " elements for " + std::to_string(keyed.times.size()) + " keys; expected " +
                  std::to_string(keyed.times.size() * per_key) +
                  (per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : ""));
  keyed.values = gltf::read_accessor(model, s.output, components, file, at + ".output");
  if (components == 4)
    for (std::size_t k = 0; k < keyed.times.size(); ++k) {
      const std::size_t e = k * per_key + (per_key == 3 ? 1 : 0);
      const Eigen::Vector4d q(keyed.values[4 * e], keyed.values[4 * e + 1], keyed.values[4 * e + 2], keyed.values[4 * e + 3]);
      if (q.norm() < 1e-9)
        gltf_fail(file, at + ".output", "key " + std::to_string(k) + " is a zero quaternion; expected unit rotations");
    }
  return keyed;
}

const char* gltf_interpolation_name(Interpolation i) {
  switch (i) {
    case Interpolation::step: return "STEP";
    case Interpolation::linear: return "LINEAR";
    case Interpolation::cubic_spline: return "CUBICSPLINE";
  }
  return "?";
}

/// The chosen animation's channels on joints (`joint_of[node]`, -1 for nodes off the skeleton).
std::vector<GltfJointChannel> gltf_read_channels(const tinygltf::Model& model, std::size_t a,
                                                 const std::vector<std::ptrdiff_t>& joint_of, const std::string& file,
                                                 std::vector<std::vector<std::string>>& described) {
  const tinygltf::Animation& animation = model.animations[a];
  std::vector<GltfJointChannel> channels;
  for (std::size_t c = 0; c < animation.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    const std::string at = gltf_indexed(gltf_indexed("animations", a) + ".channels", c);
    GltfJointChannel read;
    int components = 3;
    if (channel.target_path == "translation") {
      read.path = GltfJointChannel::Path::translation;
    } else if (channel.target_path == "rotation") {
      read.path = GltfJointChannel::Path::rotation;
      components = 4;
    } else if (channel.target_path == "scale") {
      read.path = GltfJointChannel::Path::scale;
    } else {
      continue;  // morph-target weights and extension paths do not move joints
    }
    if (channel.target_node < 0 || static_cast<std::size_t>(channel.target_node) >= model.nodes.size())
      gltf_fail(file, at + ".target.node",
                "node " + std::to_string(channel.target_node) + " out of range (the file has " +
                    std::to_string(model.nodes.size()) + ")");
    if (channel.sampler < 0 || static_cast<std::size_t>(channel.sampler) >= animation.samplers.size())
      gltf_fail(file, at + ".sampler",
                "sampler " + std::to_string(channel.sampler) + " out of range (the animation has " +
                    std::to_string(animation.samplers.size()) + ")");
    const std::ptrdiff_t joint = joint_of[static_cast<std::size_t>(channel.target_node)];
    if (joint < 0) continue;  // a node off the skeleton (a mesh, a camera)
    read.joint = static_cast<std::size_t>(joint);
    for (const GltfJointChannel& earlier : channels)
      if (earlier.joint == read.joint && earlier.path == read.path)
        gltf_fail(file, at,
                  "a second channel for node " + std::to_string(channel.target_node) + "'s " + channel.target_path +
                      "; expected one per node and path");
    read.sampler = gltf_read_sampler(model, a, channel.sampler, components, file);
    described[read.joint].push_back(channel.target_path + ":" + gltf_interpolation_name(read.sampler.interpolation));
    channels.push_back(std::move(read));
  }
  return channels;
}

/// Which nodes form the skeleton: the first skin's joints, else the animated nodes, else all;
/// with their ancestors.
std::vector<bool> gltf_skeleton_nodes(const tinygltf::Model& model, const std::vector<std::ptrdiff_t>& parents,
                                      const GltfReadOptions& options, const std::string& file) {
  std::vector<bool> selected(model.nodes.size(), false);
  const auto select = [&](int node, const std::string& path) {
    if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size())
      gltf_fail(file, path,
                "node " + std::to_string(node) + " out of range (the file has " + std::to_string(model.nodes.size()) + ")");
    for (std::ptrdiff_t at = node; at != -1 && !selected[static_cast<std::size_t>(at)];
         at = parents[static_cast<std::size_t>(at)])
      selected[static_cast<std::size_t>(at)] = true;
  };
  if (!model.skins.empty()) {
    for (std::size_t k = 0; k < model.skins[0].joints.size(); ++k)
      select(model.skins[0].joints[k], gltf_indexed("skins[0].joints", k));
  } else if (!model.animations.empty()) {
    const auto& channels = model.animations[options.animation].channels;
    for (std::size_t c = 0; c < channels.size(); ++c)
      if (channels[c].target_path != "weights")
        select(channels[c].target_node,
               gltf_indexed(gltf_indexed("animations", options.animation) + ".channels", c) + ".target.node");
  } else {
    std::fill(selected.begin(), selected.end(), true);
  }
  return selected;
}

}  // namespace

SkeletonAnimation load_gltf(const std::string& path, const GltfReadOptions& options) {
  if (!std::isfinite(options.sample_rate_hz) || options.sample_rate_hz <= 0)
    gltf_fail(path, "", "sample rate " + format_number(options.sample_rate_hz) + " Hz; expected more than 0");
  const tinygltf::Model model = gltf_load_model(path);
  if (options.animation > 0 && options.animation >= model.animations.size())
    gltf_fail(
        path, "",
        "animation " + std::to_string(options.animation) + " asked for; the file has " + std::to_string(model.animations.size()));
  const std::vector<std::ptrdiff_t> parents = gltf_node_parents(model, path);
  const std::vector<bool> selected = gltf_skeleton_nodes(model, parents, options, path);
  if (std::find(selected.begin(), selected.end(), true) == selected.end())
    gltf_fail(path, "", "no skin, no animated nodes and no nodes; expected a skeleton");

  SkeletonAnimation animation;
  animation.source = path;
  std::vector<std::ptrdiff_t> joint_of(model.nodes.size(), -1);
  std::vector<std::size_t> stack;  // depth-first from the roots, children in file order
  for (std::size_t n = model.nodes.size(); n-- > 0;)
    if (parents[n] == -1 && selected[n]) stack.push_back(n);
  std::vector<std::string> names;
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model.nodes[n];
    Joint joint;
    joint.name = node.name.empty() ? "node" + std::to_string(n) : node.name;
    if (std::find(names.begin(), names.end(), joint.name) != names.end()) joint.name += "_node" + std::to_string(n);
    names.push_back(joint.name);
    joint.parent = parents[n] == -1 ? kNoParent : joint_of[static_cast<std::size_t>(parents[n])];
    const GltfTrs trs = gltf_node_trs(node, path, gltf_indexed("nodes", n));
    joint.rest_translation = trs.translation;
    joint.rest_rotation = trs.rotation;
    joint.rest_scale = trs.scale;
    joint_of[n] = static_cast<std::ptrdiff_t>(animation.joints.size());
    animation.joints.push_back(std::move(joint));
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      if (selected[static_cast<std::size_t>(*child)]) stack.push_back(static_cast<std::size_t>(*child));
  }

  animation.channels.assign(animation.joints.size(), {});
  std::vector<GltfJointChannel> channels;
  if (!model.animations.empty()) channels = gltf_read_channels(model, options.animation, joint_of, path, animation.channels);
  double end = 0;
  for (const GltfJointChannel& channel : channels) end = std::max(end, channel.sampler.times.back());
  const double frames = std::floor(end * options.sample_rate_hz + 1e-9) + 1;
  if (!(frames <= kGltfMaxFrames))
    gltf_fail(path, "",
              "the animation lasts " + format_number(end) + " s, " + format_number(frames) + " samples at " +
                  format_number(options.sample_rate_hz) + " Hz; expected at most " + format_number(kGltfMaxFrames));
  animation.frame_time = 1.0 / options.sample_rate_hz;
  const Pose rest = rest_pose(animation);
  animation.frames.assign(static_cast<std::size_t>(frames), rest);
  for (std::size_t i = 0; i < animation.frames.size(); ++i) {
    const double t = static_cast<double>(i) / options.sample_rate_hz;
    Pose& pose = animation.frames[i];
    for (const GltfJointChannel& channel : channels) {
      const Eigen::Vector4d v = gltf::sample(channel.sampler, t);
      switch (channel.path) {
        case GltfJointChannel::Path::translation: pose.translation[channel.joint] = v.head<3>(); break;
        case GltfJointChannel::Path::scale: pose.scale[channel.joint] = v.head<3>(); break;
        case GltfJointChannel::Path::rotation: pose.rotation[channel.joint] = Eigen::Quaterniond(v[3], v[0], v[1], v[2]); break;
      }
    }
  }
  align_hemispheres(animation);
  try {
    validate(animation);
  } catch (const std::invalid_argument& e) {
    gltf_fail(path, "", e.what());
  }
  return animation;
}

}  // namespace avar::mocap
