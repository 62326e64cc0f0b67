#include "show_behaviour.hpp"

#include <set>

#include "avar/config/show_behaviour.hpp"
#include "avar/core/format.hpp"
#include "idle_section.hpp"

namespace avar::config {
namespace detail {
const char* const kBehaviourGenerators[] = {"noise", "blinks", "gaze", "breathing"};
}  // namespace detail
namespace {

/// What the show reader keeps of a behaviour for binding it to a rig later: its node and file.
struct BehaviourSource {
  YAML::Node node;
  std::string file;
};

std::string behaviour_what(const std::string& layer) { return "the behaviour of layer '" + layer + "'"; }

/// Every scalar under `node` (map keys and values), as candidate channel names.
void behaviour_scalars(const YAML::Node& node, std::set<std::string>& out) {
  if (node.IsScalar()) {
    out.insert(node.Scalar());
  } else if (node.IsSequence()) {
    for (const YAML::Node& child : node) behaviour_scalars(child, out);
  } else if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      behaviour_scalars(it->first, out);
      behaviour_scalars(it->second, out);
    }
  }
}

/// A stand-in rig for checking a behaviour without one: every name the behaviour mentions is an
/// analog channel in degrees with limits wide enough to pass anything. Only what does not depend
/// on the rig's channels can fail against it.
rig::Rig behaviour_open_rig(const YamlRef& node) {
  std::set<std::string> names;
  for (const char* g : detail::kBehaviourGenerators)
    if (auto n = node.find(g)) behaviour_scalars(n->node, names);
  constexpr double kWide = 1e9;
  rig::Rig rig;
  rig.name = "(any)";
  for (const std::string& name : names) {
    rig::ChannelSpec c;
    c.name = name;
    c.unit = "deg";
    c.min = -kWide, c.max = kWide, c.rest = 0;
    c.max_velocity = c.max_acceleration = c.max_jerk = c.ramp_velocity = kWide;
    rig.channels.push_back(c);
  }
  return rig;
}

/// The generators of a behaviour against a rig (the idle section's reader and checks).
playback::IdleSpec read_behaviour_generators(const playback::LayerBehaviour& b, const std::string& layer, const rig::Rig& rig) {
  const auto* source = std::any_cast<BehaviourSource>(&b.source);
  if (!source)
    throw InputError(b.where, behaviour_what(layer) + " was not read from a show file; expected it from load_show_file");
  playback::IdleSpec spec;
  read_idle_generators(rig, YamlRef{source->node, &source->file}, behaviour_what(layer), spec);
  return spec;
}

double behaviour_number(const YamlRef& node, std::string_view key, double fallback, const std::string& what) {
  const auto found = node.find(key);
  return found ? found->as_double(what) : fallback;
}

}  // namespace

namespace detail {

playback::LayerBehaviour read_behaviour(const YamlRef& node, const playback::Show& show, const std::string& layer) {
  const std::string what = behaviour_what(layer);
  node.expect_map(what + " ({seed, from, to, fade_in, fade_out, noise, blinks, gaze, breathing})");
  node.expect_only_keys({"seed", "from", "to", "fade_in", "fade_out", "noise", "blinks", "gaze", "breathing"}, what);
  // Look-at gaze solves the eyes' IK every tick on the loop, from the figure's pose: it lives in the
  // rig's idle section, under the show. A show aims eyes with a target instead.
  if (auto gaze = node.find("gaze"); gaze && gaze->is_map())
    if (auto look = gaze->find("look_at"))
      look->fail("look-at gaze runs from the rig's idle section, under the show; expected, in " + what +
                 ", gaze with eye channels (eyes: {pan, tilt}), or a show target that aims the eyes (targets: {EFFECTOR: {aim: "
                 "[x, y, z], ...}})");
  playback::LayerBehaviour b;
  b.where = node.where();
  if (auto seed = node.find("seed")) {
    const long long s = seed->as_integer("the seed of " + what);
    if (s < 0) seed->fail("expected the seed of " + what + " to be a whole number of at least 0, found " + seed->describe());
    b.seed = static_cast<std::uint64_t>(s);
  } else {
    // Unseeded layers differ from one another, and from run to run stay the same.
    std::uint64_t h = 1469598103934665603ULL;  // FNV-1a of the layer's name
    for (const char ch : layer) h = (h ^ static_cast<unsigned char>(ch)) * 1099511628211ULL;
    b.seed = h;
  }
  const auto seconds = [](double s) { return format_number(s) + " s"; };
  b.from = behaviour_number(node, "from", 0, "the start of " + what + " (show seconds)");
  if (b.from < 0 || b.from >= show.duration)
    node.at("from", what)
        .fail("expected the start of " + what + " within the show, from 0 to before " + seconds(show.duration) + ", found " +
              seconds(b.from));
  b.to = behaviour_number(node, "to", show.duration, "the end of " + what + " (show seconds)");
  if (b.to <= b.from || b.to > show.duration)
    node.at("to", what)
        .fail("expected the end of " + what + " after its start " + seconds(b.from) + " and by the show's end " +
              seconds(show.duration) + ", found " + seconds(b.to));
  b.fade_in = behaviour_number(node, "fade_in", 0, "fade_in (seconds)");
  b.fade_out = behaviour_number(node, "fade_out", 0, "fade_out (seconds)");
  for (const auto& [field, value] : {std::pair{"fade_in", b.fade_in}, std::pair{"fade_out", b.fade_out}})
    if (value < 0)
      node.at(field, what).fail("expected " + std::string(field) + " to be at least 0 seconds, found " + seconds(value));
  if (b.fade_in + b.fade_out > b.to - b.from)
    node.at(node.has("fade_out") ? "fade_out" : "fade_in", what)
        .fail("the fades of " + what + " (in " + seconds(b.fade_in) + " + out " + seconds(b.fade_out) +
              ") are longer than its span (" + seconds(b.to - b.from) + ", " + format_number(b.from) + " to " + seconds(b.to) +
              "); expected them to fit within it");
  b.source = BehaviourSource{node.node, *node.file};
  // Without the rig: everything the generators' reader checks that does not depend on channels.
  read_behaviour_generators(b, layer, behaviour_open_rig(node));
  return b;
}

const YAML::Node* behaviour_text(const playback::LayerBehaviour& behaviour) {
  const auto* source = std::any_cast<BehaviourSource>(&behaviour.source);
  return source ? &source->node : nullptr;
}

void check_behaviour(const playback::Layer& layer, const rig::Rig& rig, std::vector<bool>& driven, std::vector<Finding>& errors) {
  if (!layer.behaviour) return;
  try {
    playback::Layer bound = layer;
    bound.behaviour->idle = read_behaviour_generators(*layer.behaviour, layer.name, rig);
    for (const rig::ChannelSpec& c : rig.channels) bound.behaviour->channels.push_back(c.name);
    for (const std::string& name : playback::behaviour_channels(bound)) driven[*rig.find_channel(name)] = true;
  } catch (const InputError& e) {
    errors.push_back({e.where(), e.problem()});
  }
}

}  // namespace detail

void bind_show_behaviour(playback::Show& show, const rig::Rig& rig) {
  for (playback::Layer& layer : show.layers) {
    if (!layer.behaviour) continue;
    playback::LayerBehaviour& b = *layer.behaviour;
    b.idle = read_behaviour_generators(b, layer.name, rig);
    b.channels.clear();
    for (const rig::ChannelSpec& c : rig.channels) b.channels.push_back(c.name);
  }
}

bool has_unbound_behaviour(const playback::Show& show) {
  for (const playback::Layer& layer : show.layers)
    if (layer.behaviour && !layer.behaviour->bound()) return true;
  return false;
}

}  // namespace avar::config
