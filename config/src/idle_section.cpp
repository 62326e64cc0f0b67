#include "avar/config/idle_section.hpp"

#include "idle_section.hpp"
#include "idle_gaze_look_at.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "avar/core/format.hpp"
#include "avar/playback/runtime/blink_generator.hpp"

namespace avar::config {
namespace {

using playback::IdleChannelLimits;

/// A channel idle may move: named in the rig, analog.
std::size_t idle_channel(const rig::Rig& rig, const YamlRef& name_node, const std::string& what) {
  const std::string name = name_node.as_string(what);
  const auto c = rig.find_channel(name);
  if (!c) name_node.fail("expected " + what + " to be a channel of the rig, found '" + name + "'");
  if (rig.channels[*c].digital())
    name_node.fail("channel '" + name + "' is digital (it switches): idle life moves analog channels only");
  return *c;
}

double idle_positive(const YamlRef& node, const std::string& what) {
  const double v = node.as_double(what);
  if (!(v > 0)) node.fail("expected " + what + " above 0, found " + node.describe());
  return v;
}

double idle_within(const YamlRef& node, const std::string& what, double lo, double hi) {
  const double v = node.as_double(what);
  if (v < lo || v > hi)
    node.fail("expected " + what + " from " + format_number(lo) + " to " + format_number(hi) + ", found " + node.describe());
  return v;
}

/// [low, high] with low <= high (and low > 0 when `positive`).
std::pair<double, double> idle_range(const YamlRef& node, const std::string& what, bool positive) {
  node.expect_sequence(what + " ([low, high])");
  if (node.size() != 2) node.fail("expected " + what + " to be [low, high], found " + std::to_string(node.size()) + " numbers");
  const double lo = node[0].as_double("the low end of " + what);
  const double hi = node[1].as_double("the high end of " + what);
  if (positive && !(lo > 0)) node[0].fail("expected the low end of " + what + " above 0, found " + node[0].describe());
  if (hi < lo) node.fail("expected the low end of " + what + " at most its high end");
  return {lo, hi};
}

template <class F>
void idle_each(const YamlRef& map, const std::string& what, F&& f) {
  map.expect_map(what);
  for (auto it = map.node.begin(); it != map.node.end(); ++it) f(YamlRef{it->first, map.file}, YamlRef{it->second, map.file});
}

void idle_claim(std::vector<const char*>& owner, std::size_t c, const char* who, const YamlRef& where, const rig::Rig& rig) {
  if (owner[c] && owner[c] != std::string_view(who))
    where.fail("channel '" + rig.channels[c].name + "' is already driven by idle " + owner[c] + "; " + who +
               " needs a channel of its own");
  owner[c] = who;
}

playback::NoiseSpec read_noise(const rig::Rig& rig, const YamlRef& name, const YamlRef& node) {
  const std::string what = "the noise of '" + name.node.Scalar() + "'";
  node.expect_map(what + " (amplitude, frequency, octaves)");
  node.expect_only_keys({"amplitude", "frequency", "octaves"}, what);
  playback::NoiseSpec s;
  s.channel = idle_channel(rig, name, "a noise channel");
  s.amplitude = idle_positive(node.at("amplitude", what), "amplitude (channel units)");
  if (auto f = node.find("frequency")) s.frequency = idle_positive(*f, "frequency (Hz)");
  if (auto o = node.find("octaves")) s.octaves = static_cast<int>(idle_within(*o, "octaves", 1, 8));
  return s;
}

playback::BlinkSpec read_blinks(const rig::Rig& rig, const YamlRef& node, std::vector<const char*>& owner) {
  const std::string what = "the blinks";
  node.expect_map(what);
  node.expect_only_keys({"lids", "interval_s", "double_probability", "double_gap_s", "close_s", "hold_s", "open_s"}, what);
  playback::BlinkSpec s;
  idle_each(
      node.at("lids", what), "lids (a map of lid channel to its closed value)", [&](const YamlRef& name, const YamlRef& lid) {
        const std::string lwhat = "lid '" + name.node.Scalar() + "'";
        lid.expect_map(lwhat + " ({closed: V, open: V})");
        lid.expect_only_keys({"closed", "open"}, lwhat);
        playback::BlinkLid l;
        l.channel = idle_channel(rig, name, "a lid channel");
        idle_claim(owner, l.channel, "blinks", name, rig);
        const rig::ChannelSpec& ch = rig.channels[l.channel];
        const double lo = ch.min + ch.soft_margin, hi = ch.max - ch.soft_margin;
        l.closed = idle_within(lid.at("closed", lwhat), "the closed value of " + lwhat + " (inside its soft margins)", lo, hi);
        l.open =
            lid.find("open") ? idle_within(*lid.find("open"), "the open value of " + lwhat, lo, hi) : std::clamp(ch.rest, lo, hi);
        s.lids.push_back(l);
      });
  if (s.lids.empty()) node.at("lids", what).fail("expected at least one lid");
  if (auto r = node.find("interval_s")) std::tie(s.interval_min, s.interval_max) = idle_range(*r, "interval_s", true);
  if (auto p = node.find("double_probability")) s.double_probability = idle_within(*p, "double_probability", 0, 1);
  if (auto g = node.find("double_gap_s")) s.double_gap_s = idle_within(*g, "double_gap_s", 0, 2);
  if (auto c = node.find("close_s")) s.close_s = idle_positive(*c, "close_s");
  if (auto h = node.find("hold_s")) s.hold_s = idle_within(*h, "hold_s", 0, 5);
  if (auto o = node.find("open_s")) s.open_s = idle_positive(*o, "open_s");
  // A blink event (a double at worst, at the lids' own speeds) must fit in the shortest interval.
  const playback::BlinkGenerator timing(s, idle_limits(rig), 0);
  const double event = 2 * timing.blink_s() + s.double_gap_s;
  if (s.interval_min < event)
    (node.find("interval_s") ? *node.find("interval_s") : node)
        .fail("expected the shortest blink interval to be at least " + format_number(event) +
              " s (a double blink at the lids' speeds), found " + format_number(s.interval_min));
  return s;
}

/// Degrees per channel unit of an eye channel, for the vergence angle.
double idle_degrees_per_unit(const rig::ChannelSpec& c, const YamlRef& where) {
  if (c.unit == "deg" || c.unit == "°" || c.unit == "degree" || c.unit == "degrees") return 1.0;
  if (c.unit == "rad" || c.unit == "radian" || c.unit == "radians") return 180.0 / std::numbers::pi;
  where.fail("vergence needs the eye channels in deg or rad; '" + c.name + "' is in '" + c.unit + "'");
}

playback::GazeSpec read_gaze(const rig::Rig& rig, const YamlRef& node, std::vector<const char*>& owner) {
  const std::string what = "the gaze";
  node.expect_map(what);
  node.expect_only_keys({"eyes", "head", "field", "fixation_s", "near", "look_at", "distance"}, what);
  playback::GazeSpec s;
  // Eye channels moved by offsets, or (look_at) eye effectors aimed through the kinematics.
  const bool look_at = node.has("look_at");
  if (look_at && node.has("eyes")) node.at("eyes", what).fail("expected either eyes (channels) or look_at (effectors), not both");
  if (!look_at && node.has("distance"))
    node.at("distance", what).fail("distance is for look-at gaze (look_at: {effectors}); eye channels take near");
  if (look_at && node.has("near"))
    node.at("near", what).fail("near is for eye channels; look-at gaze takes distance: {far, near, near_probability}");
  const auto channel_at = [&](const YamlRef& map, std::string_view key, std::optional<std::size_t>& out) {
    if (auto n = map.find(key)) {
      out = idle_channel(rig, *n, std::string(key) + " channel");
      idle_claim(owner, *out, "gaze", *n, rig);
    }
  };
  if (!look_at) {
    const YamlRef eyes = node.at("eyes", what);
    eyes.expect_map("eyes ({pan: CH, tilt: CH} or {left_pan: CH, right_pan: CH, tilt: CH})");
    eyes.expect_only_keys({"pan", "tilt", "left_pan", "right_pan"}, "eyes");
    channel_at(eyes, "pan", s.eyes_pan);
    channel_at(eyes, "left_pan", s.left_pan);
    channel_at(eyes, "right_pan", s.right_pan);
    channel_at(eyes, "tilt", s.eyes_tilt);
    if (s.left_pan.has_value() != s.right_pan.has_value()) eyes.fail("expected both left_pan and right_pan, or neither");
    if (s.eyes_pan && s.left_pan) eyes.fail("expected either pan or left_pan and right_pan, not both");
    if (!s.eyes_pan && !s.left_pan && !s.eyes_tilt)
      eyes.fail("expected at least one eye channel (pan, left_pan/right_pan, tilt)");
  }
  if (auto head = node.find("head")) {
    head->expect_map("head ({pan: CH, tilt: CH, follow, delay_s, smoothing_s})");
    head->expect_only_keys({"pan", "tilt", "follow", "delay_s", "smoothing_s"}, "head");
    channel_at(*head, "pan", s.head_pan);
    channel_at(*head, "tilt", s.head_tilt);
    if (auto f = head->find("follow")) s.head_follow = idle_within(*f, "follow (share of the gaze the head takes)", 0, 1);
    if (auto d = head->find("delay_s")) s.head_delay_s = idle_within(*d, "delay_s", 0, 2);
    if (auto m = head->find("smoothing_s")) s.head_smoothing_s = idle_within(*m, "smoothing_s", 0.01, 5);
  }
  // The field, clipped to the room every eye channel has about its rest.
  const auto room = [&](const std::optional<std::size_t>& c, double& lo, double& hi) {
    if (!c) return;
    const rig::ChannelSpec& ch = rig.channels[*c];
    lo = std::max(lo, ch.min + ch.soft_margin - ch.rest);
    hi = std::min(hi, ch.max - ch.soft_margin - ch.rest);
  };
  if (auto field = node.find("field")) {
    field->expect_map("field ({pan: [low, high], tilt: [low, high]})");
    field->expect_only_keys({"pan", "tilt"}, "field");
    if (auto p = field->find("pan")) std::tie(s.pan_min, s.pan_max) = idle_range(*p, "the field's pan", false);
    if (auto t = field->find("tilt")) std::tie(s.tilt_min, s.tilt_max) = idle_range(*t, "the field's tilt", false);
  }
  if (look_at) {
    read_gaze_look_at(rig, node, s, owner);  // the field is in degrees of the gaze's direction
  } else {
    for (const auto& c : {s.eyes_pan, s.left_pan, s.right_pan}) room(c, s.pan_min, s.pan_max);
    room(s.eyes_tilt, s.tilt_min, s.tilt_max);
    if (!s.eyes_tilt) s.tilt_min = s.tilt_max = 0;
    if (!s.eyes_pan && !s.left_pan) s.pan_min = s.pan_max = 0;
  }
  if (s.pan_min > s.pan_max || s.tilt_min > s.tilt_max)
    node.fail("the gaze field does not overlap the eye channels' ranges (inside their soft margins)");
  if (auto f = node.find("fixation_s")) std::tie(s.fixation_min, s.fixation_max) = idle_range(*f, "fixation_s", true);
  if (auto near = node.find("near")) {
    near->expect_map("near ({probability, distance_m, interocular_m})");
    near->expect_only_keys({"probability", "distance_m", "interocular_m"}, "near");
    if (!s.left_pan) near->fail("vergence for near targets needs per-eye pan channels (eyes: {left_pan, right_pan})");
    s.near_probability = idle_within(near->at("probability", "near"), "the probability of a near target", 0, 1);
    const double distance = idle_positive(near->at("distance_m", "near"), "distance_m");
    const double interocular = near->find("interocular_m") ? idle_positive(*near->find("interocular_m"), "interocular_m") : 0.064;
    // Each eye turns inwards by atan(half the inter-ocular distance / distance).
    const double degrees = std::atan2(interocular / 2, distance) * 180.0 / std::numbers::pi;
    s.vergence = degrees / idle_degrees_per_unit(rig.channels[*s.left_pan], *near);
  }
  return s;
}

playback::BreathingSpec read_breathing(const rig::Rig& rig, const YamlRef& node) {
  const std::string what = "the breathing";
  node.expect_map(what);
  node.expect_only_keys({"period_s", "jitter", "channels"}, what);
  playback::BreathingSpec s;
  if (auto p = node.find("period_s")) s.period_s = idle_within(*p, "period_s", 0.5, 60);
  if (auto j = node.find("jitter")) s.jitter = idle_within(*j, "jitter (share of the period)", 0, 0.5);
  idle_each(
      node.at("channels", what), "channels (a map of channel to its amplitude)", [&](const YamlRef& name, const YamlRef& a) {
        playback::BreathingChannel c;
        c.channel = idle_channel(rig, name, "a breathing channel");
        c.amplitude = idle_positive(a, "the breathing amplitude of '" + name.node.Scalar() + "' (channel units, peak to peak)");
        s.channels.push_back(c);
      });
  return s;
}

}  // namespace

std::vector<IdleChannelLimits> idle_limits(const rig::Rig& rig) {
  std::vector<IdleChannelLimits> limits;
  limits.reserve(rig.channels.size());
  for (const rig::ChannelSpec& c : rig.channels)
    limits.push_back({c.min, c.max, c.soft_margin, c.rest, c.max_velocity, c.max_acceleration, c.max_jerk});
  return limits;
}

playback::IdleSpec read_idle_section(const rig::Rig& rig, const YamlRef& node) {
  node.expect_map("idle (noise, blinks, gaze, breathing)");
  node.expect_only_keys({"crossfade_s", "noise", "blinks", "gaze", "breathing"}, "idle");
  playback::IdleSpec spec;
  if (auto c = node.find("crossfade_s")) spec.crossfade_s = idle_within(*c, "crossfade_s", 0, 10);
  read_idle_generators(rig, node, "idle", spec);
  return spec;
}

void read_idle_generators(const rig::Rig& rig, const YamlRef& node, const std::string& what, playback::IdleSpec& spec) {
  spec.limits = idle_limits(rig);
  std::vector<const char*> owner(rig.channels.size(), nullptr);
  if (auto noise = node.find("noise"))
    idle_each(*noise, "noise (a map of channel to amplitude, frequency, octaves)",
              [&](const YamlRef& name, const YamlRef& n) { spec.noise.push_back(read_noise(rig, name, n)); });
  if (auto b = node.find("blinks")) spec.blinks = read_blinks(rig, *b, owner);
  if (auto g = node.find("gaze")) spec.gaze = read_gaze(rig, *g, owner);
  if (auto b = node.find("breathing")) spec.breathing = read_breathing(rig, *b);
  if (spec.noise.empty() && !spec.blinks && !spec.gaze && !spec.breathing)
    node.fail("expected at least one of noise, blinks, gaze, breathing in " + what);
}

std::optional<playback::IdleSpec> load_idle_section(const rig::Rig& rig, const std::string& path) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  const auto idle = root.find("idle");
  if (!idle) return std::nullopt;
  return read_idle_section(rig, *idle);
}

}  // namespace avar::config
