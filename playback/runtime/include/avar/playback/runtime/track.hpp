#pragma once
// A track: one keyframe curve bound by name to a channel of a rig.

#include <string>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace avar::playback {

struct Track {
  std::string channel;  ///< channel name in the rig
  RawCurve raw;         ///< the keys as authored (for checks and reports)
  Curve curve;          ///< built from raw
  SourceLocation where;
};

}  // namespace avar::playback
