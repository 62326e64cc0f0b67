#pragma once
// A show's timeline: layers of clip placements over the show's own tracks.
//
// A placement plays a clip from `start` to `end` (show seconds) through a time warp: clip time
// runs at `speed` clip seconds per show second from `offset`, forwards, or backwards from the
// clip's end when `reverse`. Its weight ramps from 0 to 1 over `fade_in` after its start and back
// to 0 over `fade_out` before its end, along a smoothstep (3x² - 2x³), so a weight is C1 inside
// the placement and two placements whose fades share a window sum to exactly 1.
//
// A layer composes its placements per channel: the layer's value is the weight-normalised sum
// of the values of the placements active on that channel, and its coverage is
// min(1, sum of their weights) × the layer's weight. Layers apply bottom (first) to top:
// override: out = out + coverage × (value - out); additive: out = out + coverage × value (the
// clips of an additive layer are offsets). A mask limits a layer to some channels.
//
// A behaviour layer (layer_behaviour.hpp) holds idle generators instead of placements: its value
// is what they write (in an additive layer, their motion about the channel's rest), its coverage
// the behaviour's span weight × the layer's weight, on every channel the generators drive.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/clip.hpp"
#include "avar/playback/runtime/layer_behaviour.hpp"

namespace avar::playback {

enum class Blend : std::uint8_t {
  override,  ///< blends from what lies below towards the layer's value by its coverage
  additive,  ///< adds the layer's value times its coverage
};

/// "override", "additive"; nullopt for anything else.
std::optional<Blend> blend_from_name(std::string_view name);
const char* to_string(Blend blend);
inline constexpr const char* kBlendNames = "override, additive";

/// A layer's value applied over `below` with `coverage` in [0, 1]. Real-time safe.
inline double apply_blend(Blend blend, double below, double value, double coverage) noexcept {
  return blend == Blend::additive ? below + coverage * value : below + coverage * (value - below);
}

/// 3x² - 2x³ on [0, 1], 0 below, 1 above: a C1 ramp with zero slope at both ends.
double smoothstep(double x) noexcept;

/// The weight of something played from `start` to `end` (seconds) at time t: 0 outside
/// [start, end], ramping up over `fade_in` after the start and down over `fade_out` before the
/// end along smoothstep. Real-time safe.
double span_weight(double t, double start, double end, double fade_in, double fade_out) noexcept;

struct Placement {
  std::size_t clip = 0;  ///< index into Show::clips
  double start = 0;      ///< show seconds
  double end = 0;        ///< show seconds, > start
  double speed = 1;      ///< clip seconds per show second, > 0
  double offset = 0;     ///< clip seconds already played at `start`, >= 0
  bool reverse = false;  ///< play the clip backwards, from its end
  double fade_in = 0;    ///< seconds, >= 0; fade_in + fade_out <= end - start
  double fade_out = 0;   ///< seconds, >= 0
  SourceLocation where;

  /// Weight at show time t (seconds): 0 outside [start, end], the fades' smoothstep ramps
  /// inside. Real-time safe.
  double weight(double t) const noexcept;
  /// The time within the curves of `placed` (the clip at index `clip`) at show time t (seconds).
  /// Real-time safe.
  double clip_time(const Clip& placed, double t) const noexcept;
};

/// A channel named in a layer's mask, with where it was named.
struct MaskChannel {
  std::string channel;
  SourceLocation where;
};

struct Layer {
  std::string name;
  Blend blend = Blend::override;
  double weight = 1;              ///< in [0, 1], scales the layer's coverage
  std::vector<MaskChannel> mask;  ///< the channels the layer may touch; empty: every one its clips drive
  std::vector<Placement> placements;  ///< a layer of clips; none on a behaviour layer
  SourceLocation where;
  std::optional<LayerBehaviour> behaviour;  ///< a behaviour layer: generators instead of clips

  /// Whether the mask lets the layer touch `channel`.
  bool touches(std::string_view channel) const noexcept;
};

/// The channels a behaviour layer bound to a rig moves: those its generators drive that its mask
/// lets it touch, in the rig's order. Empty for other layers and unbound behaviour. Allocates.
std::vector<std::string> behaviour_channels(const Layer& layer);

}  // namespace avar::playback
