#include "avar/playback/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::playback {

Sampler::Sampler(const Show& show, std::vector<std::size_t> channel_of_track, std::vector<double> defaults)
    : show_(show), channel_of_track_(std::move(channel_of_track)), defaults_(std::move(defaults)), cursors_(show.tracks.size()) {
  if (channel_of_track_.size() != show_.tracks.size()) throw std::invalid_argument("one channel index per track is needed");
  for (std::size_t c : channel_of_track_)
    if (c >= defaults_.size()) throw std::invalid_argument("a track is bound to a channel outside the frame");
}

void Sampler::sample(double show_time_s, std::span<double> frame) noexcept {
  double t = show_time_s;
  if (show_.loop && show_.duration > 0) {
    t = std::fmod(t, show_.duration);
    if (t < 0) t += show_.duration;
  }
  std::copy(defaults_.begin(), defaults_.end(), frame.begin());
  for (std::size_t i = 0; i < channel_of_track_.size(); ++i)
    frame[channel_of_track_[i]] = show_.tracks[i].curve.evaluate(t, cursors_[i]);
}

}  // namespace avar::playback
