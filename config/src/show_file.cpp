#include "avar/config/show_file.hpp"

#include <filesystem>
#include <set>

#include "avar/config/yaml_support.hpp"
#include "avar/core/format.hpp"
#include "show_clips.hpp"
#include "show_tracks.hpp"

namespace avar::config {
namespace {

using detail::constant_curve;
using detail::read_track;

/// Three curves of a target from `names` (x, y, z or roll, pitch, yaw), or a static `vector`.
void read_triple(const YamlRef& name, const YamlRef& body, double duration, const std::string& what, const char* vector,
                 const char* const (&names)[3], const char* unit, std::array<playback::RawCurve, 3>& raw,
                 std::array<playback::Curve, 3>& curves) {
  if (auto v = body.find(vector)) {
    for (const char* axis : names)
      if (body.find(axis))
        body.at(axis, "").fail(what + " has both " + vector + " and " + axis + "; expected a static " + vector + " or three curves");
    const std::string vwhat = "the " + std::string(vector) + " of " + what + " (" + unit + ")";
    v->expect_sequence(vwhat + " ([a, b, c])");
    if (v->size() != 3) v->fail("expected " + vwhat + " to have 3 numbers, found " + std::to_string(v->size()));
    for (std::size_t i = 0; i < 3; ++i)
      curves[i] = constant_curve((*v)[i].as_double(vwhat + " " + names[i]), v->where(), raw[i]);
    return;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const YamlRef curve = body.at(names[i], what + " (a static " + vector + ", or " + names[0] + ", " + names[1] + " and " +
                                                 names[2] + " curves in " + unit + ")");
    playback::Track track =
        read_track(YamlRef{YAML::Node(name.node.Scalar() + "." + names[i]), name.file}, curve, duration);
    raw[i] = std::move(track.raw);
    curves[i] = std::move(track.curve);
  }
}

/// targets: {effector: {point: [x, y, z] | x, y, z curves; aim: [x, y, z]; orientation:
/// [roll, pitch, yaw] | roll, pitch, yaw curves}}
playback::TargetTrack read_target(const YamlRef& name, const YamlRef& body, double duration) {
  playback::TargetTrack target;
  target.effector = name.as_string("an effector name");
  target.where = name.where();
  const std::string what = "target '" + target.effector + "'";
  body.expect_map(what + " (a point {point | x, y, z}, optionally aim: [x, y, z]; and/or an orientation {orientation | "
                         "roll, pitch, yaw})");
  body.expect_only_keys({"aim", "point", "x", "y", "z", "orientation", "roll", "pitch", "yaw"}, what);
  const bool point = body.has("point") || body.has("x") || body.has("y") || body.has("z");
  const bool orientation = body.has("orientation") || body.has("roll") || body.has("pitch") || body.has("yaw");
  if (!point && !orientation)
    body.fail("expected " + what + " to give a point (point: [x, y, z] or x, y, z curves) or an orientation (orientation: "
                                   "[roll, pitch, yaw] or roll, pitch, yaw curves)");
  if (auto aim = body.find("aim")) {
    if (orientation) aim->fail(what + " both aims and sets an orientation; expected one or the other");
    target.aim_axis = {0, 0, 0};
    aim->expect_sequence("the aim axis of " + what + " ([x, y, z] in the effector's frame)");
    if (aim->size() != 3) aim->fail("expected the aim axis of " + what + " to have 3 numbers [x, y, z], found " + std::to_string(aim->size()));
    for (std::size_t i = 0; i < 3; ++i) target.aim_axis[i] = (*aim)[i].as_double("the aim axis of " + what);
    if (target.aim_axis[0] == 0 && target.aim_axis[1] == 0 && target.aim_axis[2] == 0)
      aim->fail("expected the aim axis of " + what + " to be a non-zero direction, found [0, 0, 0]");
  }
  static const char* const kXyz[3] = {"x", "y", "z"};
  static const char* const kRpy[3] = {"roll", "pitch", "yaw"};
  if (point) read_triple(name, body, duration, what, "point", kXyz, "m", target.raw, target.xyz);
  if (orientation) read_triple(name, body, duration, what, "orientation", kRpy, "rad", target.raw_rpy, target.rpy);
  target.kind = !point                 ? playback::TargetKind::orientation
                : orientation          ? playback::TargetKind::pose
                : body.has("aim")      ? playback::TargetKind::aim
                                       : playback::TargetKind::position;
  return target;
}

}  // namespace

playback::Show load_show_file(const std::string& path) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  root.expect_only_keys({"name", "duration", "loop", "tracks", "targets", "clips", "layers"}, "the show file");

  playback::Show show;
  show.where = {path, 1, 1};
  show.name = root.find("name") ? root.at("name", "the show file").as_string("the show's name")
                                : std::filesystem::path(path).stem().string();
  const YamlRef duration = root.at("duration", "the show file");
  show.duration = duration.as_double("the duration (seconds)");
  if (show.duration <= 0) duration.fail("expected the duration to be more than 0 seconds, found " + duration.describe());
  if (auto loop = root.find("loop")) show.loop = loop->as_bool("loop");

  // Targets for inverse kinematics, or clips on layers, may stand in for tracks.
  const auto targets = root.find("targets");
  const YamlRef tracks = (targets || root.has("layers") || root.has("clips")) && !root.has("tracks") ? YamlRef{YAML::Node(YAML::NodeType::Map), &path}
                                                        : root.at("tracks", "the show file");
  tracks.expect_map("tracks (a map of channel name to a list of keys, or to {extrapolation, cycles, auto_smoothing, keys})");
  std::set<std::string> seen;
  for (auto it = tracks.node.begin(); it != tracks.node.end(); ++it) {
    const YamlRef name{it->first, &path};
    const std::string channel = name.as_string("a channel name");
    if (!seen.insert(channel).second) name.fail("channel '" + channel + "' has two tracks; expected one track per channel");
    show.tracks.push_back(read_track(name, YamlRef{it->second, &path}, show.duration));
  }
  if (targets) {
    targets->expect_map("targets (a map of effector name to its target point or x, y, z curves)");
    std::set<std::string> effectors;
    for (auto it = targets->node.begin(); it != targets->node.end(); ++it) {
      const YamlRef name{it->first, &path};
      if (!effectors.insert(name.as_string("an effector name")).second)
        name.fail("effector '" + name.node.Scalar() + "' has two targets; expected one target per effector");
      show.targets.push_back(read_target(name, YamlRef{it->second, &path}, show.duration));
    }
  }
  detail::read_clips_and_layers(root, show);
  return show;
}

}  // namespace avar::config
