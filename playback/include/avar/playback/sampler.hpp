#pragma once
// Samples a show into frames of channel values. Track-to-channel binding is resolved once by
// the caller; sample() then costs O(1) per track for sequential times (cached cursors).
// One thread at a time; sample() is real-time safe (no allocation, exception or lock).

#include <cstddef>
#include <span>
#include <vector>

#include "avar/playback/curve.hpp"
#include "avar/playback/show.hpp"

namespace avar::playback {

class Sampler {
 public:
  /// channel_of_track[i]: the frame index track i writes (< defaults.size()). defaults: the
  /// value of every channel no track drives; its size is the frame size. The show is borrowed
  /// and must outlive the sampler.
  Sampler(const Show& show, std::vector<std::size_t> channel_of_track, std::vector<double> defaults);

  /// Writes the whole frame for show time t (seconds). A looping show wraps t modulo its
  /// duration. frame.size() must equal the frame size.
  void sample(double show_time_s, std::span<double> frame) noexcept;

  std::size_t frame_size() const noexcept { return defaults_.size(); }

 private:
  const Show& show_;
  std::vector<std::size_t> channel_of_track_;
  std::vector<double> defaults_;
  std::vector<CurveCursor> cursors_;
};

}  // namespace avar::playback
