#pragma once
// Blender's easing equations (Robert Penner's, as blenlib easing.cc evaluates them for F-curve
// easing interpolation), with Blender's AUTO choice per family. Pure: real-time safe, any thread.

#include "avar/playback/runtime/keys.hpp"

namespace avar::playback {

/// Parameters of one easing segment.
struct EasingParams {
  double back = 1.70158;  ///< back overshoot
  double amplitude = 0;   ///< elastic, channel units; 0 = Blender's default
  double period = 0;      ///< elastic, seconds; 0 = Blender's default
};

/// The easing Blender uses for `requested` in `family`: automatic becomes ease_out for back,
/// bounce and elastic and ease_in for the others.
Easing resolved_easing(Interpolation family, Easing requested) noexcept;

/// Value of an easing segment `time` seconds after its start (0 <= time <= duration), starting
/// at `begin` and changing by `change` over `duration` seconds (> 0). `family` is one of sine ...
/// elastic; `easing` already resolved. Finite for finite inputs.
double ease(Interpolation family, Easing easing, double time, double begin, double change, double duration,
            const EasingParams& params) noexcept;

}  // namespace avar::playback
