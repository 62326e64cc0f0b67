#include "avar/config/show_file.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <set>
#include <tuple>
#include <utility>

#include "yaml_support.hpp"
#include "avar/core/format.hpp"
#include "show_clips.hpp"
#include "show_cues.hpp"
#include "show_tracks.hpp"
#include "show_visemes.hpp"
#include "yaml_vectors.hpp"

namespace avar::config {
namespace {

using detail::constant_curve;
using detail::read_key_time;
using detail::read_name;
using detail::read_track;

/// Three curves of a target from `names` (x, y, z or roll, pitch, yaw), or a static `vector`.
void read_triple(const YamlRef& name, const YamlRef& body, const std::string& what, const char* vector,
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
    playback::Track track = read_track(YamlRef{YAML::Node(name.node.Scalar() + "." + names[i]), name.file}, curve,
                                       std::numeric_limits<double>::infinity());
    raw[i] = std::move(track.raw);
    curves[i] = std::move(track.curve);
  }
}

/// speed: a shape name | {shape, k1, k2} | a user curve (keys, or {keys, ...} as a track).
playback::DistanceTime read_speed(const YamlRef& node, const std::string& what, const std::string& effector) {
  constexpr std::string_view kShapes = "linear, sine, sine_constant_middle, parabolic, cubic";
  const std::string swhat = "the speed of " + what;
  const auto shape_at = [&](const YamlRef& n) { return read_name(n, "speed shape", playback::distance_time_shape_from_name, kShapes); };
  if (!node.is_map() && !node.is_sequence()) return playback::DistanceTime(shape_at(node));
  if (node.is_map() && node.has("shape")) {
    node.expect_only_keys({"shape", "k1", "k2"}, swhat);
    const auto shape = shape_at(node.at("shape", swhat));
    const bool eased_middle = shape == playback::DistanceTimeShape::sine_constant_middle || shape == playback::DistanceTimeShape::parabolic;
    double k[2] = {0, 1};
    const char* names[2] = {"k1", "k2"};
    for (std::size_t i = 0; i < 2; ++i) {
      const auto v = node.find(names[i]);
      if (!v) continue;
      if (!eased_middle)
        v->fail("field '" + std::string(names[i]) + "' does not belong to speed shape " + to_string(shape) +
                "; expected it only with sine_constant_middle and parabolic");
      k[i] = v->as_double(std::string(names[i]) + " (normalised time)");
    }
    if (eased_middle && !(k[0] >= 0 && k[0] <= k[1] && k[1] <= 1))
      node.fail("expected 0 <= k1 <= k2 <= 1 (normalised times ending the ease in and starting the ease out) in " + swhat +
                ", found k1 " + format_number(k[0]) + ", k2 " + format_number(k[1]));
    return playback::DistanceTime(shape, k[0], k[1]);
  }
  // A user curve: normalised time -> normalised distance, written as a track's keys (named <effector>.speed).
  const playback::Track track = read_track(YamlRef{YAML::Node(effector + ".speed"), node.file}, node, 1.0);
  return playback::DistanceTime::from_keys(track.raw);
}

/// orient: frenet | tangent | {along: frenet | tangent, up: [x, y, z]} | {look_at: [x, y, z], up: [x, y, z]}
void read_orient(const YamlRef& node, const std::string& what, playback::PathSpec& spec) {
  const std::string owhat = "the orientation along the path of " + what;
  constexpr std::string_view kAlong = "frenet, tangent";
  const auto along = [&](const YamlRef& n) {
    const std::string name = n.as_string("an orientation along the path");
    if (name == "frenet") return playback::PathOrientation::frenet;
    if (name == "tangent") return playback::PathOrientation::tangent;
    n.fail("unknown orientation along the path " + n.describe() + "; expected one of: " + std::string(kAlong) +
           ", or a map {along: frenet | tangent, up: [x, y, z]} or {look_at: [x, y, z], up: [x, y, z]}");
  };
  if (!node.is_map()) {
    spec.orientation = along(node);
    return;
  }
  node.expect_only_keys({"along", "look_at", "up"}, owhat);
  if (node.has("along") == node.has("look_at"))
    node.fail("expected " + owhat + " to have either along (frenet or tangent) or look_at ([x, y, z] in metres), not " +
              (node.has("along") ? "both" : "neither"));
  if (auto a = node.find("along")) spec.orientation = along(*a);
  if (auto l = node.find("look_at")) {
    spec.orientation = playback::PathOrientation::look_at;
    spec.look_at = read_vector(*l, "the look_at point of " + what + " (m)");
  }
  if (auto u = node.find("up")) {
    if (spec.orientation == playback::PathOrientation::frenet)
      u->fail("field 'up' does not belong to a Frenet frame (its axes come from the path's bending); expected it only with "
              "along: tangent or look_at");
    spec.up = read_vector(*u, "the up vector of " + what);
    if (spec.up.isZero(0)) u->fail("expected the up vector of " + what + " to be a non-zero direction, found [0, 0, 0]");
  }
}

/// A path point: [x, y, z], or (bezier paths) {at: [x, y, z], left: [x, y, z], right: [x, y, z]}
/// with each handle optional (automatic when absent).
void read_path_point(const YamlRef& node, const std::string& what, playback::PathSpec& spec) {
  const std::string pointwhat = "a point of the path of " + what;
  spec.point_where.push_back(node.where());
  if (!node.is_map()) {
    spec.points.push_back(read_vector(node, pointwhat + " (m)"));
    spec.left.emplace_back();
    spec.right.emplace_back();
    return;
  }
  node.expect_only_keys({"at", "left", "right"}, pointwhat);
  spec.points.push_back(read_vector(node.at("at", pointwhat + " ({at: [x, y, z], left: [x, y, z], right: [x, y, z]})"), pointwhat + " (m)"));
  for (const auto& [side, handles] : {std::pair{"left", &spec.left}, std::pair{"right", &spec.right}}) {
    handles->emplace_back();
    const auto h = node.find(side);
    if (!h) continue;
    if (spec.spline != playback::PathSpline::bezier)
      h->fail("field '" + std::string(side) + "' (a handle) does not belong to a " + to_string(spec.spline) +
              " path; expected handles only on bezier paths");
    handles->back() = read_vector(*h, "the " + std::string(side) + " handle of " + pointwhat + " (m)");
  }
}

/// path: {points, spline, tension, continuity, bias, from, to, speed, orient}
playback::PathTrack read_path(const YamlRef& node, double duration, const std::string& what, const std::string& effector) {
  const std::string pwhat = "the path of " + what;
  node.expect_map(pwhat + " (a map {points, spline, from, to, speed, orient})");
  node.expect_only_keys({"points", "spline", "tension", "continuity", "bias", "from", "to", "speed", "orient"}, pwhat);
  playback::PathSpec spec;
  spec.where = node.where();
  if (auto spline = node.find("spline"))
    spec.spline = read_name(*spline, "path spline", playback::path_spline_from_name, playback::path_spline_names());
  const YamlRef points = node.at("points", pwhat);
  points.expect_sequence("the points of " + what + " (a list of [x, y, z] in metres, or on bezier paths {at, left, right})");
  if (points.size() < 2)
    points.fail("expected the path of " + what + " to have at least 2 points, found " + std::to_string(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) read_path_point(points[i], what, spec);
  if (std::all_of(spec.left.begin(), spec.left.end(), [](const auto& h) { return !h; })) spec.left.clear();
  if (std::all_of(spec.right.begin(), spec.right.end(), [](const auto& h) { return !h; })) spec.right.clear();
  const bool tcb = spec.spline == playback::PathSpline::kochanek_bartels;
  for (const auto& [field, value, belongs] : {std::tuple{"tension", &spec.tension, tcb || spec.spline == playback::PathSpline::cardinal},
                                              std::tuple{"continuity", &spec.continuity, tcb}, std::tuple{"bias", &spec.bias, tcb}}) {
    const auto v = node.find(field);
    if (!v) continue;
    if (!belongs)
      v->fail("field '" + std::string(field) + "' does not belong to a " + to_string(spec.spline) + " path; expected it only on " +
              (std::string_view(field) == "tension" ? "cardinal and kochanek_bartels paths" : "kochanek_bartels paths"));
    *value = v->as_double("the " + std::string(field));
  }
  const YamlRef from = node.at("from", pwhat + " (from: the show time in seconds when it starts)");
  const YamlRef to = node.at("to", pwhat + " (to: the show time in seconds when it ends)");
  spec.from = from.as_double("the path's start time (seconds)");
  spec.to = to.as_double("the path's end time (seconds)");
  if (spec.from < 0 || spec.from > duration)
    from.fail("path start time " + format_number(spec.from) + " s is outside the show, which runs from 0 to " + format_number(duration) + " s");
  if (spec.to > duration)
    to.fail("path end time " + format_number(spec.to) + " s is outside the show, which runs from 0 to " + format_number(duration) + " s");
  if (!(spec.to > spec.from))
    to.fail("expected the path's end time `to` (" + format_number(spec.to) + " s) to come after its start time `from` (" +
            format_number(spec.from) + " s)");
  if (auto speed = node.find("speed")) spec.speed = read_speed(*speed, what, effector);
  if (auto orient = node.find("orient")) read_orient(*orient, what, spec);
  return playback::PathTrack(std::move(spec));
}

/// orientation_keys: {order: xyz, interpolation: slerp | squad, keys: [{time, quaternion: [w, x, y, z] | euler: [x, y, z]}]}
playback::OrientationKeyTrack read_orientation_keys(const YamlRef& node, const std::string& what) {
  const std::string owhat = "the orientation keys of " + what;
  node.expect_map(owhat + " (a map {order, interpolation, keys})");
  node.expect_only_keys({"order", "interpolation", "keys"}, owhat);
  playback::OrientationKeysSpec spec;
  spec.where = node.where();
  if (auto order = node.find("order"))
    spec.order = read_name(*order, "Euler order", playback::euler_order_from_name, "xyz, xzy, yxz, yzx, zxy, zyx");
  if (auto interpolation = node.find("interpolation"))
    spec.interpolation = read_name(*interpolation, "orientation interpolation", playback::orientation_interpolation_from_name, "slerp, squad");
  const YamlRef keys = node.at("keys", owhat);
  keys.expect_sequence("the keys of " + owhat);
  if (keys.size() == 0) keys.fail("expected at least one orientation key in " + owhat + ", found none");
  bool any_euler = false;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const YamlRef k = keys[i];
    const std::string kwhat = "an orientation key of " + what + " ({time, quaternion: [w, x, y, z]} or {time, euler: [x, y, z]})";
    k.expect_map(kwhat);
    k.expect_only_keys({"time", "quaternion", "euler"}, kwhat);
    playback::OrientationKeySpec key;
    key.where = k.where();
    key.time = read_key_time(k, kwhat);
    if (k.has("quaternion") == k.has("euler"))
      k.fail("expected " + kwhat + " to have either quaternion or euler, not " + (k.has("euler") ? "both" : "neither"));
    if (auto q = k.find("quaternion")) {
      q->expect_sequence("a quaternion ([w, x, y, z])");
      if (q->size() != 4) q->fail("expected a quaternion [w, x, y, z] of 4 numbers, found " + std::to_string(q->size()));
      key.quaternion = Eigen::Quaterniond((*q)[0].as_double("w"), (*q)[1].as_double("x"), (*q)[2].as_double("y"), (*q)[3].as_double("z"));
      if (key.quaternion->norm() == 0) q->fail("expected a quaternion [w, x, y, z] of a rotation, found [0, 0, 0, 0]");
    } else {
      key.euler = read_vector(*k.find("euler"), "Euler angles (radians)");
      any_euler = true;
    }
    spec.keys.push_back(key);
  }
  if (node.has("order") && !any_euler)
    node.at("order", owhat).fail("an Euler order without Euler keys; expected `order` only when some key has euler angles");
  return playback::OrientationKeyTrack(std::move(spec));
}

/// targets: {effector: {point: [x, y, z] | x, y, z curves | path; aim: [x, y, z]; orientation:
/// [roll, pitch, yaw] | roll, pitch, yaw curves | orientation_keys}}
playback::TargetTrack read_target(const YamlRef& name, const YamlRef& body, double duration) {
  playback::TargetTrack target;
  target.effector = name.as_string("an effector name");
  target.where = name.where();
  const std::string what = "target '" + target.effector + "'";
  body.expect_map(what + " (a point {point | x, y, z | path}, optionally aim: [x, y, z]; and/or an orientation {orientation | "
                         "roll, pitch, yaw | orientation_keys})");
  body.expect_only_keys({"aim", "point", "x", "y", "z", "path", "orientation", "roll", "pitch", "yaw", "orientation_keys"}, what);
  const bool curves_point = body.has("point") || body.has("x") || body.has("y") || body.has("z");
  const bool curves_orientation = body.has("orientation") || body.has("roll") || body.has("pitch") || body.has("yaw");
  if (auto path = body.find("path")) {
    if (curves_point) path->fail(what + " has both a path and a point; expected one or the other");
    target.path.emplace(read_path(*path, duration, what, target.effector));
  }
  if (auto keys = body.find("orientation_keys")) {
    if (curves_orientation)
      keys->fail(what + " has both orientation_keys and an orientation (orientation or roll, pitch, yaw); expected one or the other");
    if (target.path && target.path->orients())
      keys->fail(what + " has orientation_keys and a path that orients it; expected one or the other");
    target.orientation_keys.emplace(read_orientation_keys(*keys, what));
  }
  if (target.path && target.path->orients() && curves_orientation)
    body.fail("expected " + what + " to take its orientation from its path or from orientation / roll, pitch, yaw, not both");
  const bool point = curves_point || target.path;
  const bool orientation = curves_orientation || target.orientation_keys || (target.path && target.path->orients());
  if (!point && !orientation)
    body.fail("expected " + what + " to give a point (point: [x, y, z], x, y, z curves or a path) or an orientation (orientation: "
                                   "[roll, pitch, yaw], roll, pitch, yaw curves or orientation_keys)");
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
  if (curves_point) read_triple(name, body, what, "point", kXyz, "m", target.raw, target.xyz);
  if (curves_orientation) read_triple(name, body, what, "orientation", kRpy, "rad", target.raw_rpy, target.rpy);
  target.kind = !point                 ? playback::TargetKind::orientation
                : orientation          ? playback::TargetKind::pose
                : body.has("aim")      ? playback::TargetKind::aim
                                       : playback::TargetKind::position;
  return target;
}

playback::Show show_from_yaml(const YAML::Node& root_node, const std::string& path) {
  const YamlRef root{root_node, &path};
  root.expect_only_keys({"name", "duration", "loop", "tracks", "targets", "clips", "layers", "visemes", "cues", "markers"},
                        "the show file");

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
  const YamlRef tracks = (targets || root.has("layers") || root.has("clips") || root.has("visemes")) && !root.has("tracks")
                             ? YamlRef{YAML::Node(YAML::NodeType::Map), &path}
                             : root.at("tracks", "the show file");
  tracks.expect_map("tracks (a map of channel name to a list of keys, or to {extrapolation, cycles, auto_smoothing, keys})");
  std::set<std::string> seen;
  for (auto it = tracks.node.begin(); it != tracks.node.end(); ++it) {
    const YamlRef name{it->first, &path};
    const std::string channel = name.as_string("a channel name");
    if (!seen.insert(channel).second) name.fail("channel '" + channel + "' has two tracks; expected one track per channel");
    show.tracks.push_back(read_track(name, YamlRef{it->second, &path}, show.duration));
  }
  if (auto visemes = root.find("visemes")) detail::read_show_visemes(*visemes, show);
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
  if (auto cues = root.find("cues")) detail::read_cues(*cues, show);
  if (auto markers = root.find("markers")) detail::read_markers(*markers, show);
  return show;
}

}  // namespace

playback::Show load_show_file(const std::string& path) { return show_from_yaml(load_yaml_file(path), path); }

playback::Show load_show_text(const std::string& text, const std::string& path) {
  return show_from_yaml(parse_yaml_text(text, path), path);
}

playback::RawKey load_key_text(const std::string& text, const std::string& channel, const std::string& source) {
  const std::string& path = source;
  // The key's place in its track is not known here: in_slope is let through (the curve build
  // reads it only where a hermite segment ends).
  return detail::read_key(YamlRef{parse_yaml_text(text, path), &path}, channel, playback::Interpolation::hermite);
}

}  // namespace avar::config
