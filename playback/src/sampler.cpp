#include "avar/playback/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace avar::playback {

Sampler::Sampler(const Show& show, std::span<const std::size_t> channel_of_track, std::span<const double> defaults)
    : show_(show),
      channel_of_track_(channel_of_track.begin(), channel_of_track.end()),
      defaults_(defaults.begin(), defaults.end()),
      cursors_(show.tracks.size()) {
  if (channel_of_track_.size() != show_.tracks.size())
    throw std::invalid_argument("the show has " + std::to_string(show_.tracks.size()) + " tracks but " +
                                std::to_string(channel_of_track_.size()) + " channel indices were given; expected one per track");
  std::vector<bool> taken(defaults_.size(), false);
  for (std::size_t i = 0; i < channel_of_track_.size(); ++i) {
    const std::size_t c = channel_of_track_[i];
    if (c >= defaults_.size())
      throw std::invalid_argument("track '" + show_.tracks[i].channel + "' is bound to frame index " + std::to_string(c) +
                                  "; expected an index below the frame size " + std::to_string(defaults_.size()));
    if (taken[c])
      throw std::invalid_argument("track '" + show_.tracks[i].channel + "' is bound to frame index " + std::to_string(c) +
                                  ", which another track already drives; expected one track per channel");
    taken[c] = true;
  }
  for (std::size_t c = 0; c < defaults_.size(); ++c)
    if (!std::isfinite(defaults_[c]))
      throw std::invalid_argument("the default of frame index " + std::to_string(c) + " is not finite; expected a finite value");
}

void Sampler::sample(double show_time_s, std::span<double> frame) noexcept {
  if (frame.size() != defaults_.size()) return;
  const double t = show_.local_time(show_time_s);
  std::copy(defaults_.begin(), defaults_.end(), frame.begin());
  for (std::size_t i = 0; i < channel_of_track_.size(); ++i)
    frame[channel_of_track_[i]] = show_.tracks[i].curve.evaluate(t, cursors_[i]);
}

}  // namespace avar::playback
