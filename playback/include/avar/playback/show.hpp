#pragma once
// A show: tracks of keyframe curves, each bound by name to a channel of a rig, played over a
// duration, once or looping.

#include <string>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/curve.hpp"

namespace avar::playback {

struct Track {
  std::string channel;  ///< channel name in the rig
  RawCurve raw;         ///< the keys as authored (for checks and reports)
  Curve curve;          ///< built from raw
  SourceLocation where;
};

struct Show {
  std::string name;
  double duration = 0;  ///< seconds, > 0
  bool loop = false;
  std::vector<Track> tracks;
  SourceLocation where;
};

}  // namespace avar::playback
