#include "show_clips.hpp"

#include <map>
#include <set>
#include <string>

#include "avar/core/format.hpp"
#include "show_behaviour.hpp"
#include "show_tracks.hpp"

namespace avar::config::detail {
namespace {

using playback::Clip;
using playback::ClipMode;

std::string seconds(double s) { return format_number(s) + " s"; }

/// Key times of a clip's track lie in [0, clip duration]: a clip is placed, stretched and looped by
/// its span. Checked before the track is read.
void check_key_times(const YamlRef& body, const Clip& clip, const std::string& channel) {
  const YamlRef keys = body.is_map() && body.has("keys") ? body.at("keys", "") : body;
  if (!keys.is_sequence()) return;  // read_track says what is wrong
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (!keys[i].is_map()) continue;
    const auto time = keys[i].find("time");
    if (!time) continue;
    const double t = time->as_double("the key time (seconds)");
    if (t < 0 || t > clip.duration)
      time->fail("key time " + seconds(t) + " of track '" + channel + "' is outside clip '" + clip.name + "', which runs from 0 to " +
                 seconds(clip.duration));
  }
}

Clip read_clip(const YamlRef& name, const YamlRef& body) {
  Clip clip;
  clip.name = name.as_string("a clip name");
  clip.where = name.where();
  const std::string what = "clip '" + clip.name + "'";
  body.expect_map(what + " ({duration, mode, tracks})");
  body.expect_only_keys({"duration", "mode", "tracks"}, what);
  const YamlRef duration = body.at("duration", what);
  clip.duration = duration.as_double("the duration of " + what + " (seconds)");
  if (clip.duration <= 0) duration.fail("expected the duration of " + what + " to be more than 0 seconds, found " + duration.describe());
  if (auto mode = body.find("mode")) clip.mode = read_name(*mode, "clip mode", playback::clip_mode_from_name, playback::kClipModeNames);
  const YamlRef tracks = body.at("tracks", what);
  tracks.expect_map("the tracks of " + what + " (a map of channel name to keys)");
  if (tracks.size() == 0) tracks.fail(what + " has no tracks; expected at least one channel with keys");
  std::set<std::string> seen;
  for (auto it = tracks.node.begin(); it != tracks.node.end(); ++it) {
    const YamlRef channel{it->first, name.file};
    const YamlRef keys{it->second, name.file};
    if (!seen.insert(channel.as_string("a channel name")).second)
      channel.fail("channel '" + channel.node.Scalar() + "' has two tracks in " + what + "; expected one track per channel");
    check_key_times(keys, clip, channel.node.Scalar());
    clip.tracks.push_back(read_track(channel, keys, clip.duration));
  }
  return clip;
}

double optional_number(const YamlRef& node, std::string_view key, double fallback, const std::string& what) {
  const auto found = node.find(key);
  return found ? found->as_double(what) : fallback;
}

playback::Placement read_placement(const YamlRef& node, const playback::Show& show, const std::string& layer) {
  const std::string what = "a placement in layer '" + layer + "'";
  node.expect_map(what + " ({clip, start, end, speed, offset, reverse, fade_in, fade_out})");
  node.expect_only_keys({"clip", "start", "end", "speed", "offset", "reverse", "fade_in", "fade_out"}, what);
  playback::Placement p;
  p.where = node.where();
  const YamlRef clip_name = node.at("clip", what);
  const std::string name = clip_name.as_string("a clip name");
  std::string names;
  for (std::size_t i = 0; i < show.clips.size(); ++i) {
    if (show.clips[i].name == name) p.clip = i;
    names += (names.empty() ? "" : ", ") + show.clips[i].name;
  }
  if (p.clip >= show.clips.size() || show.clips[p.clip].name != name)
    clip_name.fail("unknown clip '" + name + "'; expected one of the show's clips: " + (names.empty() ? "(none)" : names));
  const Clip& clip = show.clips[p.clip];

  p.start = optional_number(node, "start", 0, "the start (show seconds)");
  if (p.start < 0 || p.start >= show.duration)
    node.at("start", what).fail("expected the start of clip '" + name + "' within the show, from 0 to before " + seconds(show.duration) +
                                ", found " + seconds(p.start));
  p.speed = optional_number(node, "speed", 1, "the speed (clip seconds per show second)");
  if (p.speed <= 0)
    node.at("speed", what).fail("expected the speed of clip '" + name + "' to be more than 0 clip seconds per show second (reverse: true "
                                "plays it backwards), found " + format_number(p.speed));
  p.offset = optional_number(node, "offset", 0, "the offset (clip seconds)");
  if (p.offset < 0 || (clip.mode == ClipMode::hold && p.offset >= clip.duration))
    node.at("offset", what).fail("expected the offset into clip '" + name + "' to be at least 0" +
                                 (clip.mode == ClipMode::hold ? " and below its duration " + seconds(clip.duration) : std::string()) +
                                 ", found " + seconds(p.offset));
  if (auto reverse = node.find("reverse")) p.reverse = reverse->as_bool("reverse");
  if (auto end = node.find("end")) {
    p.end = end->as_double("the end (show seconds)");
    if (p.end <= p.start || p.end > show.duration)
      end->fail("expected the end of clip '" + name + "' after its start " + seconds(p.start) + " and by the show's end " +
                seconds(show.duration) + ", found " + seconds(p.end));
  } else {
    p.end = clip.mode == ClipMode::hold ? p.start + (clip.duration - p.offset) / p.speed : show.duration;
    if (p.end > show.duration)
      node.fail("clip '" + name + "' from " + seconds(p.start) + " at speed " + format_number(p.speed) + " ends at " + seconds(p.end) +
                ", after the show's end " + seconds(show.duration) + "; expected it to end by then (give an end, or lengthen the show)");
  }
  p.fade_in = optional_number(node, "fade_in", 0, "fade_in (seconds)");
  p.fade_out = optional_number(node, "fade_out", 0, "fade_out (seconds)");
  for (const auto& [field, value] : {std::pair{"fade_in", p.fade_in}, std::pair{"fade_out", p.fade_out}})
    if (value < 0) node.at(field, what).fail("expected " + std::string(field) + " to be at least 0 seconds, found " + seconds(value));
  if (p.fade_in + p.fade_out > p.end - p.start)
    node.at(node.has("fade_out") ? "fade_out" : "fade_in", what)
        .fail("the fades of clip '" + name + "' (in " + seconds(p.fade_in) + " + out " + seconds(p.fade_out) + ") are longer than its placement (" +
              seconds(p.end - p.start) + ", " + format_number(p.start) + " to " + seconds(p.end) + "); expected them to fit within it");
  return p;
}

playback::Layer read_layer(const YamlRef& node, std::size_t index, const playback::Show& show) {
  node.expect_map("a layer ({name, blend, weight, channels, clips | behaviour})");
  node.expect_only_keys({"name", "blend", "weight", "channels", "clips", "behaviour"}, "a layer");
  playback::Layer layer;
  layer.where = node.where();
  layer.name = node.find("name") ? node.at("name", "").as_string("the layer's name") : "layer " + std::to_string(index + 1);
  const std::string what = "layer '" + layer.name + "'";
  if (auto blend = node.find("blend")) layer.blend = read_name(*blend, "blend", playback::blend_from_name, playback::kBlendNames);
  if (auto weight = node.find("weight")) {
    layer.weight = weight->as_double("the weight of " + what);
    if (layer.weight < 0 || layer.weight > 1) weight->fail("expected the weight of " + what + " within [0, 1], found " + weight->describe());
  }
  if (auto channels = node.find("channels")) {
    channels->expect_sequence("the channels (mask) of " + what);
    if (channels->size() == 0)
      channels->fail("the mask of " + what + " lists no channels; expected at least one (leave channels out for every channel its clips drive)");
    for (std::size_t i = 0; i < channels->size(); ++i) {
      const YamlRef channel = (*channels)[i];
      playback::MaskChannel m{channel.as_string("a channel name"), channel.where()};
      for (const playback::MaskChannel& other : layer.mask)
        if (other.channel == m.channel) channel.fail("channel '" + m.channel + "' is listed twice in the mask of " + what + "; expected each once");
      layer.mask.push_back(std::move(m));
    }
  }
  if (auto behaviour = node.find("behaviour")) {
    if (node.has("clips"))
      behaviour->fail(what +
                      " has both clips and behaviour; expected one or the other (put the behaviour on a layer of its own)");
    layer.behaviour = read_behaviour(*behaviour, show, layer.name);
    return layer;
  }
  if (!node.has("clips"))
    node.fail(what +
              " has neither clips nor behaviour; expected clips: [{clip, start, ...}] or behaviour: {noise, blinks, gaze, "
              "breathing, ...}");
  const YamlRef placements = node.at("clips", what);
  placements.expect_sequence("the clips of " + what + " (a list of {clip, start, ...})");
  if (placements.size() == 0) placements.fail(what + " places no clips; expected at least one");
  for (std::size_t i = 0; i < placements.size(); ++i) layer.placements.push_back(read_placement(placements[i], show, layer.name));
  return layer;
}

}  // namespace

void read_clips_and_layers(const YamlRef& root, playback::Show& show) {
  if (auto clips = root.find("clips")) {
    clips->expect_map("clips (a map of clip name to {duration, mode, tracks})");
    for (auto it = clips->node.begin(); it != clips->node.end(); ++it) {
      const YamlRef name{it->first, root.file};
      for (const Clip& other : show.clips)
        if (other.name == name.as_string("a clip name")) name.fail("clip '" + other.name + "' is defined twice; expected unique clip names");
      show.clips.push_back(read_clip(name, YamlRef{it->second, root.file}));
    }
  }
  const auto layers = root.find("layers");
  if (!layers) {
    if (root.has("clips"))
      root.at("clips", "").fail("the show has clips but no layers; expected layers: placing them on the timeline");
    return;
  }
  layers->expect_sequence("layers (a list of {name, blend, weight, channels, clips | behaviour}, bottom first)");
  if (layers->size() == 0) layers->fail("layers lists no layers; expected at least one, or no layers section");
  for (std::size_t i = 0; i < layers->size(); ++i) {
    playback::Layer layer = read_layer((*layers)[i], i, show);
    for (const playback::Layer& other : show.layers)
      if (other.name == layer.name)
        (*layers)[i].fail("layer '" + layer.name + "' is named twice; expected unique layer names");
    show.layers.push_back(std::move(layer));
  }
}

}  // namespace avar::config::detail
