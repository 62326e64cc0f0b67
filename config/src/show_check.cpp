#include "avar/core/format.hpp"
#include "avar/config/show_check.hpp"

#include <algorithm>
#include <cmath>

#include "played_span.hpp"
#include "show_behaviour.hpp"

namespace avar::config {
namespace {

std::string limits_text(const rig::ChannelSpec& c) {
  return "[" + format_number(c.min) + ", " + format_number(c.max) + "]" + (c.unit.empty() ? "" : " " + c.unit);
}

/// Scans the played part [t0, t1] of the curve between keys k and k + 1 on a fine grid for its
/// extreme values.
void check_segment_overshoot(const playback::Track& track, std::size_t k, double t0, double t1, const rig::ChannelSpec& c,
                             std::vector<Finding>& warnings) {
  const auto& keys = track.raw.keys;
  constexpr int kSamplesPerSegment = 256;
  double lo = std::min(track.curve.evaluate(t0), track.curve.evaluate(t1));
  double hi = std::max(track.curve.evaluate(t0), track.curve.evaluate(t1));
  for (int i = 1; i < kSamplesPerSegment; ++i) {
    const double v = track.curve.evaluate(t0 + (t1 - t0) * i / kSamplesPerSegment);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo < c.min || hi > c.max)
    warnings.push_back({keys[k].where, "the curve of '" + c.name + "' between " + format_number(t0) + " s and " + format_number(t1) +
                                           " s reaches " + format_number(lo < c.min ? lo : hi) + ", outside its limits " +
                                           limits_text(c) + "; it will be clamped"});
}

/// Clips and layers: every channel a clip drives or a mask names must be the rig's; the channels
/// that layers touch count as driven. Clip key values are offsets in additive layers, so their
/// range is checked on the composed motion (check_feasibility), not here.
void check_layers(const playback::Show& show, const rig::Rig& rig, std::vector<bool>& driven, ShowCheck& result) {
  const auto unknown = [&](const SourceLocation& where, const std::string& what, const std::string& channel) {
    result.errors.push_back({where, "unknown channel '" + channel + "' in " + what + "; expected one of the rig '" + rig.name +
                                        "' channels: " + rig.channel_names()});
  };
  for (const playback::Clip& clip : show.clips)
    for (const playback::Track& track : clip.tracks)
      if (!rig.find_channel(track.channel)) unknown(track.where, "clip '" + clip.name + "'", track.channel);
  for (const playback::Layer& layer : show.layers) {
    for (const playback::MaskChannel& m : layer.mask)
      if (!rig.find_channel(m.channel)) unknown(m.where, "the mask of layer '" + layer.name + "'", m.channel);
    detail::check_behaviour(layer, rig, driven, result.errors);
    for (const playback::Placement& p : layer.placements)
      for (const playback::Track& track : show.clips[p.clip].tracks)
        if (const auto ci = rig.find_channel(track.channel); ci && layer.touches(track.channel)) driven[*ci] = true;
  }
}

/// A key outside the show (before 0, after its duration) is not played as it is: the curve it
/// shapes is, from the show's start or up to its end. An error when that value is outside the
/// channel's limits, named at the nearest key outside. Returns whether both ends are in range.
bool check_played_ends(const playback::Track& track, double duration, const rig::ChannelSpec& c, std::vector<Finding>& errors) {
  const auto& keys = track.raw.keys;
  bool in_range = true;
  const auto check = [&](double t, const playback::RawKey& outside, const char* end) {
    const double v = track.curve.evaluate(t);
    if (v >= c.min && v <= c.max) return;
    in_range = false;
    errors.push_back({outside.where, "the curve of '" + c.name + "' is at " + format_number(v) + " at the show's " + end + " (" +
                                         format_number(t) + " s), shaped by the key at " + format_number(outside.time) +
                                         " s outside the show; expected it within the channel's limits " + limits_text(c)});
  };
  const auto first_played = std::find_if(keys.begin(), keys.end(), [](const playback::RawKey& k) { return k.time >= 0; });
  if (first_played != keys.begin()) check(0, *(first_played - 1), "start");
  const auto after = std::find_if(keys.begin(), keys.end(), [&](const playback::RawKey& k) { return k.time > duration; });
  if (after != keys.end()) check(duration, *after, "end");
  return in_range;
}

/// Whether a track of the show, or of a clip that a layer lets touch it, drives `channel`.
const playback::Track* track_driving(const playback::Show& show, const std::string& channel) {
  for (const playback::Track& track : show.tracks)
    if (track.channel == channel) return &track;
  for (const playback::Layer& layer : show.layers)
    for (const playback::Placement& p : layer.placements)
      for (const playback::Track& track : show.clips[p.clip].tracks)
        if (track.channel == channel && layer.touches(channel)) return &track;
  return nullptr;
}

}  // namespace

std::string Finding::to_string() const { return avar::to_string(where) + ": " + message; }

ShowCheck check_show_against_rig(const playback::Show& show, const rig::Rig& rig) {
  ShowCheck result;
  // A digital cue switches a digital channel (its step track is checked with the tracks below).
  for (const playback::Cue& cue : show.cues) {
    if (cue.is_osc()) continue;
    const auto ci = rig.find_channel(cue.digital_channel);
    if (ci && !rig.channels[*ci].digital())
      result.errors.push_back({cue.where, "a digital cue switches channel '" + cue.digital_channel +
                                              "', which is analog; give the channel kind: digital or key it with a track"});
  }
  std::vector<bool> driven(rig.channels.size(), false);
  for (const playback::Track& track : show.tracks) {
    const auto ci = rig.find_channel(track.channel);
    if (!ci) {
      result.errors.push_back({track.where, "unknown channel '" + track.channel + "'; expected one of the rig '" + rig.name +
                                                "' channels: " + rig.channel_names()});
      continue;
    }
    driven[*ci] = true;
    const rig::ChannelSpec& c = rig.channels[*ci];
    const auto& keys = track.raw.keys;
    bool keys_in_range = check_played_ends(track, show.duration, c, result.errors);
    for (const playback::RawKey& key : keys) {
      if (!detail::played(key.time, show.duration)) continue;
      if (key.value < c.min || key.value > c.max) {
        keys_in_range = false;
        result.errors.push_back({key.where, "value " + format_number(key.value) + " at " + format_number(key.time) + " s is outside channel '" +
                                                c.name + "' limits " + limits_text(c)});
      }
    }
    if (!keys_in_range) continue;
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      if (keys[k].interpolation != playback::Interpolation::bezier) continue;
      if (const auto span = detail::played_part(keys[k].time, keys[k + 1].time, show.duration))
        check_segment_overshoot(track, k, span->t0, span->t1, c, result.warnings);
    }
  }
  check_layers(show, rig, driven, result);
  // Targets: the rig must have the effector; the joints that move it drive their channels, which
  // must not also have tracks.
  for (const playback::TargetTrack& target : show.targets) {
    if (!rig.kinematics) {
      result.errors.push_back({target.where, "target '" + target.effector + "' needs inverse kinematics, but rig '" + rig.name +
                                                 "' has no kinematics section; expected a rig with joints and effectors"});
      continue;
    }
    const auto effector = rig.kinematics->model.find_effector(target.effector);
    if (!effector) {
      std::string names;
      for (const kinematics::Effector& e : rig.kinematics->model.effectors()) names += (names.empty() ? "" : ", ") + e.name;
      result.errors.push_back({target.where, "unknown effector '" + target.effector + "'; expected one of the rig's effectors: " +
                                                 (names.empty() ? "(none)" : names)});
      continue;
    }
    for (std::size_t b : rig::bindings_moving(*rig.kinematics, *effector)) {
      const std::size_t channel = rig.kinematics->bindings[b].channel;
      if (const playback::Track* track = track_driving(show, rig.channels[channel].name))
        result.errors.push_back({track->where, "channel '" + track->channel + "' is moved by target '" + target.effector +
                                                   "' (inverse kinematics) and also has a track; expected one or the other"});
      driven[channel] = true;
    }
  }
  for (std::size_t i = 0; i < rig.channels.size(); ++i)
    if (!driven[i])
      result.warnings.push_back({show.where, "no track drives channel '" + rig.channels[i].name + "'; it holds its rest pose " +
                                                 format_number(rig.channels[i].rest)});
  return result;
}

}  // namespace avar::config
