#pragma once
// Behaviour placed on a show's layer: the rig idle section's generators (noise, blinks, gaze,
// breathing; idle_spec.hpp) played over a span of the show, faded in and out like a clip
// placement, under the layer's blend, weight and mask (timeline.hpp).
//
// A show file names channels; the generators need the rig's channels and limits. The show reader
// keeps the behaviour's text in `source` and checks it without a rig as far as it can; binding
// it to a rig (config::bind_show_behaviour) fills `idle` and `channels`. A Sampler refuses an
// unbound behaviour.

#include <any>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

struct LayerBehaviour {
  std::uint64_t seed = 0;  ///< the same seed gives the same motion at the same show times
  double from = 0;         ///< show seconds: the span the behaviour plays
  double to = 0;           ///< show seconds, > from
  double fade_in = 0;      ///< seconds, >= 0; fade_in + fade_out <= to - from (smoothstep, as placements)
  double fade_out = 0;
  IdleSpec idle;                      ///< once bound: channel indices into `channels`, limits one per channel
  std::vector<std::string> channels;  ///< once bound: the names of idle's channels (the rig's, in order)
  std::any source;                    ///< the show reader's record of the generators' text, for binding
  SourceLocation where;

  bool bound() const noexcept { return !channels.empty(); }
  /// Weight at show time t (seconds): 0 outside [from, to], the fades' smoothstep ramps inside.
  /// Real-time safe.
  double weight(double t) const noexcept;
};

}  // namespace avar::playback
