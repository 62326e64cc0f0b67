#include "avar/control/idle_layer.hpp"

#include <stdexcept>
#include <string>

namespace avar::control {
namespace {

std::vector<std::size_t> idle_layer_channels(const playback::IdleGenerator& idle) {
  std::vector<std::size_t> channels;
  for (std::size_t c = 0; c < idle.drives().size(); ++c)
    if (idle.drives()[c]) channels.push_back(c);
  return channels;
}

std::vector<MixerLayer> idle_mixer_layers(const std::vector<std::size_t>& channels, double crossfade_s) {
  std::vector<MixerLayer> layers;
  layers.reserve(channels.size());
  for (const std::size_t c : channels) layers.push_back({"idle/" + std::to_string(c), c, 0, Blend::override, crossfade_s, 0});
  return layers;
}

std::unique_ptr<GazeLookAt> idle_layer_look_at(const playback::IdleSpec& spec, const rig::RigKinematics* kinematics) {
  if (!spec.gaze || !spec.gaze->look_at) return nullptr;
  if (!kinematics) throw std::invalid_argument("look-at gaze needs the rig's kinematics");
  return std::make_unique<GazeLookAt>(*kinematics, *spec.gaze->look_at, spec.limits);
}

}  // namespace

std::vector<char> show_drives(const rig::Rig& rig, const playback::Show& show) {
  std::vector<char> drives(rig.channels.size(), 0);
  const auto by_name = [&](const std::string& name) {
    if (const auto c = rig.find_channel(name)) drives[*c] = 1;
  };
  for (const playback::Track& t : show.tracks) by_name(t.channel);
  for (const playback::Clip& clip : show.clips)
    for (const playback::Track& t : clip.tracks) by_name(t.channel);
  for (const playback::Layer& layer : show.layers)
    for (const std::string& name : playback::behaviour_channels(layer)) by_name(name);
  if (rig.kinematics)
    for (const playback::TargetTrack& target : show.targets)
      if (const auto e = rig.kinematics->model.find_effector(target.effector))
        for (const std::size_t b : rig::bindings_moving(*rig.kinematics, *e)) drives[rig.kinematics->bindings[b].channel] = 1;
  return drives;
}

IdleLayer::IdleLayer(const playback::IdleSpec& spec, std::uint64_t seed, std::vector<char> show_drives,
                     const rig::RigKinematics* kinematics)
    : look_at_(idle_layer_look_at(spec, kinematics)),
      idle_(spec, seed),
      show_drives_(std::move(show_drives)),
      channels_(idle_layer_channels(idle_)),
      layer_of_(spec.limits.size(), channels_.size()),
      mixer_(spec.limits.size(), idle_mixer_layers(channels_, spec.crossfade_s)),
      idle_frame_(spec.limits.size()) {
  if (show_drives_.size() != spec.limits.size())
    throw std::invalid_argument("the show's channel mask has " + std::to_string(show_drives_.size()) + " channels, idle " +
                                std::to_string(spec.limits.size()));
  for (std::size_t i = 0; i < channels_.size(); ++i) layer_of_[channels_[i]] = i;
  for (std::size_t c = 0; c < idle_frame_.size(); ++c) idle_frame_[c] = spec.limits[c].rest;
  idle_.set_gaze_aim(look_at_.get());
}

bool IdleLayer::show_playing() const noexcept {
  if (!controller_) return false;
  // Idle lets go early enough to be gone when the show starts.
  const double t = controller_->show_time();
  return t >= -idle_.spec().crossfade_s && t < controller_->show_end();
}

void IdleLayer::apply(double now_s, std::span<double> frame) noexcept {
  if (frame.size() != idle_frame_.size()) return;
  // The channels idle leaves alone pose the figure as the layers under it do (the look-at
  // eyes are aimed with it).
  const std::span<const char> drives = idle_.drives();
  for (std::size_t c = 0; c < frame.size(); ++c)
    if (!drives[c]) idle_frame_[c] = frame[c];
  idle_.sample(now_s, idle_frame_);
  const bool playing = show_playing();
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const std::size_t c = channels_[i];
    if (playing && show_drives_[c]) mixer_.release(i);
    else mixer_.set(i, idle_frame_[c], now_s);
  }
  mixer_.mix(frame, now_s);
}

double IdleLayer::weight(std::size_t channel) const noexcept {
  return channel < layer_of_.size() && layer_of_[channel] < channels_.size() ? mixer_.weight(layer_of_[channel]) : 0.0;
}

}  // namespace avar::control
