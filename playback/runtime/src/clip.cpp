#include "avar/playback/runtime/clip.hpp"

#include <algorithm>
#include <cmath>

namespace avar::playback {
namespace {

/// x wrapped into [0, period).
double wrap(double x, double period) noexcept {
  const double w = std::fmod(x, period);
  return w < 0 ? w + period : w;
}

}  // namespace

std::optional<ClipMode> clip_mode_from_name(std::string_view name) {
  if (name == "hold") return ClipMode::hold;
  if (name == "loop") return ClipMode::loop;
  if (name == "ping_pong") return ClipMode::ping_pong;
  return std::nullopt;
}

const char* to_string(ClipMode mode) {
  switch (mode) {
    case ClipMode::hold: return "hold";
    case ClipMode::loop: return "loop";
    case ClipMode::ping_pong: return "ping_pong";
  }
  return "hold";
}

double Clip::local_time(double played) const noexcept {
  if (std::isnan(played) || !(duration > 0)) return 0;
  switch (mode) {
    case ClipMode::hold: break;
    case ClipMode::loop:
      if (std::isfinite(played)) return wrap(played, duration);
      break;
    case ClipMode::ping_pong:
      if (std::isfinite(played)) {
        const double w = wrap(played, 2 * duration);
        return w <= duration ? w : 2 * duration - w;
      }
      break;
  }
  return std::clamp(played, 0.0, duration);
}

}  // namespace avar::playback
