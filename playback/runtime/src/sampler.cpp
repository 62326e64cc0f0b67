#include "avar/playback/runtime/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace avar::playback {
namespace {

std::size_t frame_index(std::span<const std::string> frame_channels, const std::string& channel, const std::string& user) {
  const auto it = std::find(frame_channels.begin(), frame_channels.end(), channel);
  if (it != frame_channels.end()) return static_cast<std::size_t>(it - frame_channels.begin());
  std::string names;
  for (const std::string& n : frame_channels) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument(user + " names channel '" + channel +
                              "', which the frame does not have; expected one of: " + names);
}

}  // namespace

Sampler::Sampler(const Show& show, std::span<const std::size_t> channel_of_track, std::span<const double> defaults)
    : show_(show), defaults_(defaults.begin(), defaults.end()) {
  if (show_.layered())
    throw std::invalid_argument(
        "the show has layers of clips; expected the sampler to be given the frame's channel names to bind them");
  bind_tracks(channel_of_track);
}

Sampler::Sampler(const Show& show, std::span<const std::string> frame_channels, std::span<const double> defaults)
    : show_(show), defaults_(defaults.begin(), defaults.end()) {
  if (frame_channels.size() != defaults_.size())
    throw std::invalid_argument(std::to_string(frame_channels.size()) + " frame channel names but " +
                                std::to_string(defaults_.size()) + " defaults were given; expected one default per channel");
  std::vector<std::size_t> binding;
  for (const Track& track : show_.tracks)
    binding.push_back(frame_index(frame_channels, track.channel, "track '" + track.channel + "'"));
  bind_tracks(binding);
  bind_layers(frame_channels);
}

void Sampler::bind_tracks(std::span<const std::size_t> channel_of_track) {
  channel_of_track_.assign(channel_of_track.begin(), channel_of_track.end());
  cursors_.assign(show_.tracks.size(), CurveCursor{});
  if (channel_of_track_.size() != show_.tracks.size())
    throw std::invalid_argument("the show has " + std::to_string(show_.tracks.size()) + " tracks but " +
                                std::to_string(channel_of_track_.size()) + " channel indices were given; expected one per track");
  std::vector<bool> taken(defaults_.size(), false);
  for (std::size_t i = 0; i < channel_of_track_.size(); ++i) {
    const std::size_t c = channel_of_track_[i];
    if (c >= defaults_.size())
      throw std::invalid_argument("track '" + show_.tracks[i].channel + "' is bound to frame index " + std::to_string(c) +
                                  "; expected an index below the frame size " + std::to_string(defaults_.size()));
    if (taken[c])
      throw std::invalid_argument("track '" + show_.tracks[i].channel + "' is bound to frame index " + std::to_string(c) +
                                  ", which another track already drives; expected one track per channel");
    taken[c] = true;
  }
  for (std::size_t c = 0; c < defaults_.size(); ++c)
    if (!std::isfinite(defaults_[c]))
      throw std::invalid_argument("the default of frame index " + std::to_string(c) + " is not finite; expected a finite value");
}

void Sampler::bind_layers(std::span<const std::string> frame_channels) {
  for (const Layer& layer : show_.layers) {
    const std::string who = "layer '" + layer.name + "'";
    for (const MaskChannel& m : layer.mask) frame_index(frame_channels, m.channel, "the mask of " + who);
    LayerRun run{&layer, placements_.size(), placements_.size(), slots_.size(), slots_.size(), 0};
    if (layer.behaviour) {
      bind_behaviour(layer, frame_channels, run);
      layers_.push_back(run);
      continue;
    }
    for (const Placement& placement : layer.placements) {
      if (placement.clip >= show_.clips.size())
        throw std::invalid_argument(who + " places clip " + std::to_string(placement.clip) + "; expected an index below the " +
                                    std::to_string(show_.clips.size()) + " clips of the show");
      const Clip& clip = show_.clips[placement.clip];
      PlacementRun p{&placement, &clip, clip_tracks_.size(), clip_tracks_.size()};
      for (const Track& track : clip.tracks) {
        const std::size_t channel = frame_index(frame_channels, track.channel, "clip '" + clip.name + "'");
        if (!layer.touches(track.channel)) continue;
        const auto slot = std::find_if(slots_.begin() + static_cast<std::ptrdiff_t>(run.first_slot), slots_.end(),
                                       [&](const Slot& s) { return s.channel == channel; });
        const std::size_t slot_index = static_cast<std::size_t>(slot - slots_.begin());
        if (slot == slots_.end()) slots_.push_back({channel, 0, 0});
        clip_tracks_.push_back({&track.curve, slot_index, {}});
      }
      p.end_track = clip_tracks_.size();
      placements_.push_back(p);
    }
    run.end_placement = placements_.size();
    run.end_slot = slots_.size();
    layers_.push_back(run);
  }
}

void Sampler::bind_behaviour(const Layer& layer, std::span<const std::string> frame_channels, LayerRun& run) {
  const LayerBehaviour& b = *layer.behaviour;
  if (!b.bound())
    throw std::invalid_argument(
        "layer '" + layer.name +
        "' has behaviour not bound to a rig; expected config::bind_show_behaviour to give it the rig's channels");
  if (b.channels.size() != b.idle.limits.size())
    throw std::invalid_argument("the behaviour of layer '" + layer.name + "' names " + std::to_string(b.channels.size()) +
                                " channels for " + std::to_string(b.idle.limits.size()) + " limits; expected one name per limit");
  run.behaviour = behaviours_.size();
  BehaviourRun r{BehaviourPlayer(b.idle, b.seed), std::vector<double>(b.channels.size()), behaviour_channels_.size(), 0};
  for (std::size_t c = 0; c < b.channels.size(); ++c) {
    r.values[c] = b.idle.limits[c].rest;
    if (!r.player.drives()[c] || !layer.touches(b.channels[c])) continue;
    const std::size_t f = frame_index(frame_channels, b.channels[c], "the behaviour of layer '" + layer.name + "'");
    behaviour_channels_.push_back({c, f, b.idle.limits[c].rest});
  }
  r.end_channel = behaviour_channels_.size();
  behaviours_.push_back(std::move(r));
}

void Sampler::compose_behaviour(const LayerRun& run, double t, std::span<double> frame) noexcept {
  const Layer& layer = *run.layer;
  const LayerBehaviour& b = *layer.behaviour;
  const double w = b.weight(t);
  if (!(w > 0)) return;
  BehaviourRun& r = behaviours_[run.behaviour];
  r.player.sample(t - b.from, r.values);
  const double coverage = w * layer.weight;
  for (std::size_t i = r.first_channel; i < r.end_channel; ++i) {
    const BehaviourChannel& c = behaviour_channels_[i];
    const double value = layer.blend == Blend::additive ? r.values[c.idle] - c.rest : r.values[c.idle];
    frame[c.frame] = apply_blend(layer.blend, frame[c.frame], value, coverage);
  }
}

void Sampler::compose_layer(LayerRun& run, double t, std::span<double> frame) noexcept {
  if (run.layer->behaviour) {
    compose_behaviour(run, t, frame);
    return;
  }
  for (std::size_t s = run.first_slot; s < run.end_slot; ++s) slots_[s].weighted_sum = slots_[s].weight_sum = 0;
  for (std::size_t p = run.first_placement; p < run.end_placement; ++p) {
    const PlacementRun& placement = placements_[p];
    const double w = placement.placement->weight(t);
    if (!(w > 0)) continue;
    const double u = placement.placement->clip_time(*placement.clip, t);
    for (std::size_t i = placement.first_track; i < placement.end_track; ++i) {
      ClipTrack& track = clip_tracks_[i];
      Slot& slot = slots_[track.slot];
      slot.weighted_sum += w * track.curve->evaluate(u, track.cursor);
      slot.weight_sum += w;
    }
  }
  const Layer& layer = *run.layer;
  for (std::size_t s = run.first_slot; s < run.end_slot; ++s) {
    const Slot& slot = slots_[s];
    if (!(slot.weight_sum > 0)) continue;
    const double coverage = std::min(1.0, slot.weight_sum) * layer.weight;
    frame[slot.channel] = apply_blend(layer.blend, frame[slot.channel], slot.weighted_sum / slot.weight_sum, coverage);
  }
}

void Sampler::sample(double show_time_s, std::span<double> frame) noexcept {
  if (frame.size() != defaults_.size()) return;
  const double t = show_.local_time(show_time_s);
  std::copy(defaults_.begin(), defaults_.end(), frame.begin());
  for (std::size_t i = 0; i < channel_of_track_.size(); ++i)
    frame[channel_of_track_[i]] = show_.tracks[i].curve.evaluate(t, cursors_[i]);
  for (LayerRun& run : layers_) compose_layer(run, t, frame);
  warm();
}

void Sampler::warm() noexcept {
  const std::size_t tracks = cursors_.size(), total = tracks + clip_tracks_.size();
  if (total == 0) return;
  if (warm_next_ >= total) warm_next_ = 0;
  if (warm_next_ < tracks) {
    warm_sink_ = show_.tracks[warm_next_].curve.warm(cursors_[warm_next_]);
  } else {
    const ClipTrack& track = clip_tracks_[warm_next_ - tracks];
    warm_sink_ = track.curve->warm(track.cursor);
  }
  ++warm_next_;
}

}  // namespace avar::playback
