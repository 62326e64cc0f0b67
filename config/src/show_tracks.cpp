#include "show_tracks.hpp"

#include "avar/core/format.hpp"
#include "show_audio_track.hpp"

namespace avar::config::detail {
namespace {

using playback::Interpolation;

playback::Handle read_handle(const YamlRef& node, std::string_view what) {
  if (!node.is_sequence() || node.size() != 2)
    node.fail("expected " + std::string(what) + " to be [time, value], found " + node.describe());
  return {node[0].as_double(std::string(what) + " time"), node[1].as_double(std::string(what) + " value")};
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

playback::Cycles read_cycles(const YamlRef& node, const std::string& channel) {
  const std::string what = "the cycles of track '" + channel + "'";
  node.expect_map(what);
  node.expect_only_keys({"before", "after", "before_count", "after_count"}, what);
  playback::Cycles cycles;
  constexpr std::string_view kModes = "none, repeat, repeat_offset, mirror";
  if (auto m = node.find("before")) cycles.before = read_name(*m, "cycle mode", playback::cycle_mode_from_name, kModes);
  if (auto m = node.find("after")) cycles.after = read_name(*m, "cycle mode", playback::cycle_mode_from_name, kModes);
  for (const auto& [field, count] :
       {std::pair{"before_count", &cycles.before_count}, std::pair{"after_count", &cycles.after_count}}) {
    if (auto c = node.find(field)) {
      const long long n = c->as_integer("a cycle count");
      if (n < 0 || n > 1000000000) c->fail("expected a cycle count of 0 (forever) or more, found " + c->describe());
      *count = static_cast<int>(n);
    }
  }
  return cycles;
}

}  // namespace

playback::RawKey read_key(const YamlRef& node, const std::string& channel, std::optional<Interpolation> previous) {
  const std::string what = "a key of track '" + channel + "'";
  node.expect_map(what);
  node.expect_only_keys({"time", "value", "interpolation", "left", "right", "left_type", "right_type", "easing", "back", "amplitude",
                         "period", "in_slope", "out_slope", "tension", "continuity", "bias"},
                        what);
  playback::RawKey key;
  key.where = node.where();
  key.time = read_key_time(node, what);
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

double read_key_time(const YamlRef& key, std::string_view what) {
  return key.at("time", what).as_double("the key time (seconds)");
}

playback::Track read_track(const YamlRef& name, const YamlRef& body, double span_s) {
  const std::string channel = name.as_string("a channel name");
  playback::Track track;
  track.channel = channel;
  track.where = name.where();
  track.raw.where = name.where();
  YamlRef keys = body;
  if (body.is_map() && body.has("audio")) {
    body.expect_only_keys({"audio"}, "track '" + channel + "' made from audio (audio: {file, open, ...} and nothing else)");
    return read_audio_track(name, body.at("audio", "track '" + channel + "'"), span_s);
  }
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
    track.raw.keys.push_back(read_key(keys[i], channel, previous));
    previous = track.raw.keys.back().interpolation;
  }
  track.curve = playback::Curve::build(track.raw);
  return track;
}

playback::Curve constant_curve(double value, const SourceLocation& where, playback::RawCurve& raw) {
  playback::RawKey key;
  key.value = value;
  key.where = where;
  raw.keys = {key};
  raw.where = where;
  return playback::Curve::build(raw);
}

}  // namespace avar::config::detail
