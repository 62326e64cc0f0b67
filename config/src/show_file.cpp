#include "avar/core/format.hpp"
#include "avar/config/show_file.hpp"

#include <filesystem>
#include <set>

#include "avar/config/yaml_support.hpp"

namespace avar::config {
namespace {

using playback::Interpolation;

playback::Handle read_handle(const YamlRef& node, std::string_view what) {
  if (!node.is_sequence() || node.size() != 2)
    node.fail("expected " + std::string(what) + " to be [time, value], found " + node.describe());
  return {node[0].as_double(std::string(what) + " time"), node[1].as_double(std::string(what) + " value")};
}

// A name from one of the curve vocabularies, or a failure listing the accepted ones.
template <typename Parse>
auto read_name(const YamlRef& node, std::string_view what, Parse parse, std::string_view accepted) {
  const auto parsed = parse(node.as_string(what));
  if (!parsed) node.fail("unknown " + std::string(what) + " " + node.describe() + "; expected one of: " + std::string(accepted));
  return *parsed;
}

// Fields that only some interpolations read; anywhere else they are a mistake.
struct FieldRule {
  std::string_view field;
  bool (*belongs)(Interpolation own, std::optional<Interpolation> previous);
  std::string_view where_it_belongs;
};
constexpr FieldRule kFieldRules[] = {
    {"easing", [](Interpolation i, auto) { return playback::is_easing_family(i); },
     "keys with an easing interpolation (sine, quad, cubic, quart, quint, expo, circ, back, bounce, elastic)"},
    {"back", [](Interpolation i, auto) { return i == Interpolation::back; }, "back keys"},
    {"amplitude", [](Interpolation i, auto) { return i == Interpolation::elastic; }, "elastic keys"},
    {"period", [](Interpolation i, auto) { return i == Interpolation::elastic; }, "elastic keys"},
    {"tension", [](Interpolation i, auto) { return i == Interpolation::cardinal || i == Interpolation::kochanek_bartels; },
     "cardinal and kochanek_bartels keys"},
    {"continuity", [](Interpolation i, auto) { return i == Interpolation::kochanek_bartels; }, "kochanek_bartels keys"},
    {"bias", [](Interpolation i, auto) { return i == Interpolation::kochanek_bartels; }, "kochanek_bartels keys"},
    {"out_slope", [](Interpolation i, auto) { return i == Interpolation::hermite; }, "hermite keys"},
    {"in_slope", [](Interpolation, std::optional<Interpolation> p) { return p == Interpolation::hermite; },
     "keys that end a hermite segment (after a hermite key)"},
};

playback::RawKey read_key(const YamlRef& node, double duration, const std::string& channel, std::optional<Interpolation> previous) {
  const std::string what = "a key of track '" + channel + "'";
  node.expect_map(what);
  node.expect_only_keys({"time", "value", "interpolation", "left", "right", "left_type", "right_type", "easing", "back", "amplitude",
                         "period", "in_slope", "out_slope", "tension", "continuity", "bias"},
                        what);
  playback::RawKey key;
  key.where = node.where();
  const YamlRef time = node.at("time", what);
  key.time = time.as_double("the key time (seconds)");
  if (key.time < 0 || key.time > duration)
    time.fail("key time " + format_number(key.time) + " s is outside the show, which runs from 0 to " + format_number(duration) + " s");
  key.value = node.at("value", what).as_double("the key value");
  if (auto interp = node.find("interpolation"))
    key.interpolation = read_name(*interp, "interpolation", playback::interpolation_from_name, playback::interpolation_names());
  for (const FieldRule& rule : kFieldRules)
    if (auto field = node.find(rule.field); field && !rule.belongs(key.interpolation, previous))
      field->fail("field '" + std::string(rule.field) + "' does not belong to a key with " + to_string(key.interpolation) +
                  " interpolation; expected it only on " + std::string(rule.where_it_belongs));
  if (auto left = node.find("left")) key.left = read_handle(*left, "the left handle");
  if (auto right = node.find("right")) key.right = read_handle(*right, "the right handle");
  constexpr std::string_view kHandleTypes = "free, aligned, vector, auto, auto_clamped";
  if (auto t = node.find("left_type")) key.left_type = read_name(*t, "handle type", playback::handle_type_from_name, kHandleTypes);
  if (auto t = node.find("right_type")) key.right_type = read_name(*t, "handle type", playback::handle_type_from_name, kHandleTypes);
  if (auto e = node.find("easing")) key.easing = read_name(*e, "easing", playback::easing_from_name, "auto, ease_in, ease_out, ease_in_out");
  if (auto v = node.find("back")) key.back = v->as_double("back (the overshoot)");
  if (auto v = node.find("amplitude")) key.amplitude = v->as_double("the amplitude (channel units)");
  if (auto v = node.find("period")) key.period = v->as_double("the period (seconds)");
  if (auto v = node.find("in_slope")) key.in_slope = v->as_double("in_slope (units per second)");
  if (auto v = node.find("out_slope")) key.out_slope = v->as_double("out_slope (units per second)");
  if (auto v = node.find("tension")) key.tension = v->as_double("the tension");
  if (auto v = node.find("continuity")) key.continuity = v->as_double("the continuity");
  if (auto v = node.find("bias")) key.bias = v->as_double("the bias");
  return key;
}

playback::Cycles read_cycles(const YamlRef& node, const std::string& channel) {
  const std::string what = "the cycles of track '" + channel + "'";
  node.expect_map(what);
  node.expect_only_keys({"before", "after", "before_count", "after_count"}, what);
  playback::Cycles cycles;
  constexpr std::string_view kModes = "none, repeat, repeat_offset, mirror";
  if (auto m = node.find("before")) cycles.before = read_name(*m, "cycle mode", playback::cycle_mode_from_name, kModes);
  if (auto m = node.find("after")) cycles.after = read_name(*m, "cycle mode", playback::cycle_mode_from_name, kModes);
  for (const auto& [field, count] : {std::pair{"before_count", &cycles.before_count}, std::pair{"after_count", &cycles.after_count}}) {
    if (auto c = node.find(field)) {
      const long long n = c->as_integer("a cycle count");
      if (n < 0 || n > 1000000000) c->fail("expected a cycle count of 0 (forever) or more, found " + c->describe());
      *count = static_cast<int>(n);
    }
  }
  return cycles;
}

playback::Track read_track(const YamlRef& name, const YamlRef& body, double duration) {
  const std::string channel = name.as_string("a channel name");
  playback::Track track;
  track.channel = channel;
  track.where = name.where();
  track.raw.where = name.where();
  YamlRef keys = body;
  if (body.is_map()) {
    const std::string what = "track '" + channel + "'";
    body.expect_only_keys({"extrapolation", "cycles", "auto_smoothing", "keys"}, what);
    if (auto e = body.find("extrapolation"))
      track.raw.extrapolation = read_name(*e, "extrapolation", playback::extrapolation_from_name, "constant, linear");
    if (auto s = body.find("auto_smoothing"))
      track.raw.auto_smoothing = read_name(*s, "auto_smoothing", playback::auto_smoothing_from_name, "none, continuous_acceleration");
    if (auto c = body.find("cycles")) track.raw.cycles = read_cycles(*c, channel);
    keys = body.at("keys", what);
  }
  keys.expect_sequence("the keys of track '" + channel + "'");
  if (keys.size() == 0) name.fail("track '" + channel + "' has no keys; expected at least one");
  std::optional<Interpolation> previous;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    track.raw.keys.push_back(read_key(keys[i], duration, channel, previous));
    previous = track.raw.keys.back().interpolation;
  }
  track.curve = playback::Curve::build(track.raw);
  return track;
}

/// A constant one-key curve, for a static target point.
playback::Curve constant_curve(double value, const SourceLocation& where, playback::RawCurve& raw) {
  playback::RawKey key;
  key.value = value;
  key.where = where;
  raw.keys = {key};
  raw.where = where;
  return playback::Curve::build(raw);
}

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
  root.expect_only_keys({"name", "duration", "loop", "tracks", "targets"}, "the show file");

  playback::Show show;
  show.where = {path, 1, 1};
  show.name = root.find("name") ? root.at("name", "the show file").as_string("the show's name")
                                : std::filesystem::path(path).stem().string();
  const YamlRef duration = root.at("duration", "the show file");
  show.duration = duration.as_double("the duration (seconds)");
  if (show.duration <= 0) duration.fail("expected the duration to be more than 0 seconds, found " + duration.describe());
  if (auto loop = root.find("loop")) show.loop = loop->as_bool("loop");

  // Targets for inverse kinematics may stand in for tracks.
  const auto targets = root.find("targets");
  const YamlRef tracks = targets && !root.has("tracks") ? YamlRef{YAML::Node(YAML::NodeType::Map), &path}
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
  return show;
}

}  // namespace avar::config
