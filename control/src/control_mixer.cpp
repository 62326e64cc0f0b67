#include "avar/control/control_mixer.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace avar::control {
using playback::smoothstep;

ControlMixer::ControlMixer(std::size_t channels, std::vector<MixerLayer> layers)
    : layers_(std::move(layers)), order_(layers_.size()), state_(layers_.size()) {
  for (const MixerLayer& l : layers_) {
    if (l.channel >= channels)
      throw std::invalid_argument("layer '" + l.name + "' names channel " + std::to_string(l.channel) + " of " +
                                  std::to_string(channels));
    if (!(l.crossfade_s >= 0) || !(l.silence_timeout_s >= 0))
      throw std::invalid_argument("layer '" + l.name + "': crossfade and timeout must be 0 or more seconds");
  }
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  // By priority, then declaration order (a plain sort with the tie broken: stable_sort would take
  // a temporary buffer through the nothrow operator new).
  std::sort(order_.begin(), order_.end(), [this](std::size_t a, std::size_t b) {
    return layers_[a].priority != layers_[b].priority ? layers_[a].priority < layers_[b].priority : a < b;
  });
}

void ControlMixer::set(std::size_t layer, double value, double now_s) noexcept {
  State& s = state_[layer];
  s.value = value;
  s.last_set_s = now_s;
  s.active = true;
}

void ControlMixer::update(std::size_t layer, double value) noexcept {
  if (state_[layer].active) state_[layer].value = value;
}

void ControlMixer::release(std::size_t layer) noexcept { state_[layer].active = false; }

double ControlMixer::weight(std::size_t layer) const noexcept { return smoothstep(state_[layer].ramp); }

std::size_t ControlMixer::find(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < layers_.size(); ++i)
    if (layers_[i].name == name) return i;
  return layers_.size();
}

void ControlMixer::mix(std::span<double> frame, double now_s) noexcept {
  const double dt = mixed_ ? std::max(0.0, now_s - last_mix_s_) : 0.0;
  last_mix_s_ = now_s;
  mixed_ = true;
  for (const std::size_t i : order_) {
    const MixerLayer& l = layers_[i];
    State& s = state_[i];
    if (s.active && l.silence_timeout_s > 0 && now_s - s.last_set_s > l.silence_timeout_s) s.active = false;
    const double goal = s.active ? 1.0 : 0.0;
    if (l.crossfade_s <= 0) {
      s.ramp = goal;
    } else {
      const double step = dt / l.crossfade_s;
      s.ramp = goal > s.ramp ? std::min(goal, s.ramp + step) : std::max(goal, s.ramp - step);
    }
    if (s.ramp <= 0 || l.channel >= frame.size()) continue;
    frame[l.channel] = playback::apply_blend(l.blend, frame[l.channel], s.value, smoothstep(s.ramp));
  }
}

void ControlMixer::reset() noexcept {
  std::fill(state_.begin(), state_.end(), State{});
  mixed_ = false;
  last_mix_s_ = 0;
}

}  // namespace avar::control
