#pragma once
// Arbitration of what drives each channel: the show's value at the bottom, then layers in
// priority order. An override layer replaces what is below it, weighted by its crossfade
// weight; an additive layer adds its value (an offset, channel units) times its weight. A layer
// becomes active when set() gives it a value and goes quiet when its silence timeout passes
// with no new value, or on release(); its weight ramps to 1 or 0 over its crossfade time, eased
// (smoothstep), so hand-over both ways is continuous in value and in slope. The result still
// goes through the limiter: the mixer never decides what the hardware can do.

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "avar/playback/runtime/timeline.hpp"

namespace avar::control {

// Blending is the timeline's own (playback::Blend, apply_blend): a live layer composes like a
// show's layer of clips.
using playback::Blend;

struct MixerLayer {
  std::string name;
  std::size_t channel = 0;  ///< index into the frame
  int priority = 0;         ///< higher wins; equal priorities mix in declaration order
  Blend blend = Blend::override;
  double crossfade_s = 0.3;      ///< time for the weight to go 0 -> 1 or 1 -> 0; 0 = at once
  double silence_timeout_s = 0;  ///< release after this long without set(); 0 = never
};

class ControlMixer {
 public:
  /// `channels`: the frame's size; every layer's channel must be below it and crossfade and
  /// timeout >= 0 (std::invalid_argument otherwise). Allocates; the rest is real-time safe.
  ControlMixer(std::size_t channels, std::vector<MixerLayer> layers);

  /// Gives layer `layer` (declaration index) a value at loop time now_s and activates it.
  void set(std::size_t layer, double value, double now_s) noexcept;
  /// Changes an active layer's value without counting as activity (a smoothed control still
  /// settling after its last message); an inactive layer ignores it.
  void update(std::size_t layer, double value) noexcept;
  /// Deactivates the layer: its weight fades to 0 over its crossfade.
  void release(std::size_t layer) noexcept;
  /// Mixes the active layers into `frame` (in: the values below every layer) at now_s, which
  /// must not go back in time; advances the weights by the time since the last mix.
  void mix(std::span<double> frame, double now_s) noexcept;
  /// Every layer inactive with weight 0, the clock forgotten.
  void reset() noexcept;

  std::size_t size() const noexcept { return layers_.size(); }
  const MixerLayer& layer(std::size_t i) const noexcept { return layers_[i]; }
  /// The eased weight the last mix used, 0..1.
  double weight(std::size_t layer) const noexcept;
  bool active(std::size_t layer) const noexcept { return state_[layer].active; }
  double value(std::size_t layer) const noexcept { return state_[layer].value; }
  /// Declaration index of the layer called `name`, or size().
  std::size_t find(std::string_view name) const noexcept;

 private:
  struct State {
    double value = 0;
    double last_set_s = 0;
    double ramp = 0;  ///< 0..1, linear in time; the weight is its smoothstep
    bool active = false;
  };
  std::vector<MixerLayer> layers_;
  std::vector<std::size_t> order_;  ///< layer indices by ascending priority (stable)
  std::vector<State> state_;
  double last_mix_s_ = 0;
  bool mixed_ = false;
};

}  // namespace avar::control
