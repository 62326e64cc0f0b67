#pragma once
// Samples a show into frames of channel values, tick by tick. The caller resolves which frame
// slot each track drives once, at load time; sample() then costs O(1) per track for sequential
// times (one cached cursor per track, allocated at construction).
//
// Thread and real-time safety: construction allocates and may throw (load time). sample() is
// real-time safe: no allocation, exception, lock, I/O or logging. A Sampler keeps its cursors,
// so one Sampler is used by one thread at a time; several Samplers (one per thread) may share
// one Show, which is only read.

#include <cstddef>
#include <span>
#include <vector>

#include "avar/playback/curve.hpp"
#include "avar/playback/show.hpp"

namespace avar::playback {

class Sampler {
 public:
  /// channel_of_track[i]: the frame index that show.tracks[i] writes. defaults: the value of
  /// every channel that no track drives (channel units); its size is the frame size. Both are
  /// copied. The show is borrowed: it must outlive the sampler and stay unchanged. Throws
  /// std::invalid_argument when there is not exactly one index per track, an index is outside
  /// the frame, two tracks share an index, or a default is not finite.
  Sampler(const Show& show, std::span<const std::size_t> channel_of_track, std::span<const double> defaults);

  /// Writes every channel of `frame` for show time `show_time_s` (seconds): the driven channels
  /// from their tracks, the others from the defaults. A looping show wraps the time modulo its
  /// duration (negative times included); a show played once holds its first values before 0 and
  /// its last values after the end. Every value written is finite. Precondition:
  /// frame.size() == frame_size(); a frame of another size is left untouched. Real-time safe.
  void sample(double show_time_s, std::span<double> frame) noexcept;

  std::size_t frame_size() const noexcept { return defaults_.size(); }

 private:
  const Show& show_;
  std::vector<std::size_t> channel_of_track_;
  std::vector<double> defaults_;
  std::vector<CurveCursor> cursors_;
};

}  // namespace avar::playback
