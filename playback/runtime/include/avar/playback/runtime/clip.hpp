#pragma once
// A clip: tracks over a clip-local time from 0 to its duration, and what happens when the time
// runs past its end (hold the end, loop, or ping-pong). Layers place clips on a show's timeline
// (timeline.hpp).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::playback {

enum class ClipMode : std::uint8_t {
  hold,       ///< plays once; before 0 the first values, after the end the last values
  loop,       ///< repeats from 0 after the end
  ping_pong,  ///< plays forwards, then backwards, then forwards...
};

/// "hold", "loop", "ping_pong"; nullopt for anything else.
std::optional<ClipMode> clip_mode_from_name(std::string_view name);
const char* to_string(ClipMode mode);
inline constexpr const char* kClipModeNames = "hold, loop, ping_pong";

struct Clip {
  std::string name;
  double duration = 0;  ///< clip seconds, > 0; every key time lies in [0, duration]
  ClipMode mode = ClipMode::hold;
  std::vector<Track> tracks;  ///< at least one, one per channel
  SourceLocation where;

  /// The time within the clip's curves, in [0, duration], for `played` clip seconds since the
  /// clip's start (any real: negative before the start, beyond the duration after its end),
  /// as the mode maps it. A NaN gives 0. Real-time safe.
  double local_time(double played) const noexcept;
};

}  // namespace avar::playback
