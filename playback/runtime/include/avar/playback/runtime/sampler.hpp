#pragma once
// Samples a show into frames of channel values, tick by tick. The caller resolves which frame
// slot each track drives once, at load time; sample() then costs O(1) per track for sequential
// times (one cached cursor per track, and per track of every clip placement, allocated at
// construction). A layered show is composed as timeline.hpp describes: the show's tracks (or the
// defaults) first, then each layer bottom to top.
//
// Thread and real-time safety: construction allocates and may throw (load time). sample() is
// real-time safe: no allocation, exception, lock, I/O or logging. A Sampler keeps its cursors,
// so one Sampler is used by one thread at a time; several Samplers (one per thread) may share
// one Show, which is only read.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "avar/playback/runtime/behaviour_player.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::playback {

class Sampler {
 public:
  /// For a plain show (no layers). channel_of_track[i]: the frame index that show.tracks[i]
  /// writes. defaults: the value of every channel that no track drives (channel units); its size
  /// is the frame size. Both are copied. The show is borrowed: it must outlive the sampler and
  /// stay unchanged. Throws std::invalid_argument when the show has layers, there is not exactly
  /// one index per track, an index is outside the frame, two tracks share an index, or a default
  /// is not finite.
  Sampler(const Show& show, std::span<const std::size_t> channel_of_track, std::span<const double> defaults);

  /// For any show, plain or layered: frame_channels[i] names frame index i, and every channel a
  /// track, a clip or a layer's mask names must be among them. defaults as above, one per frame
  /// channel. Throws std::invalid_argument for a name the frame does not have, a placement of a
  /// clip the show does not have, sizes that differ, a behaviour layer not bound to a rig
  /// (config::bind_show_behaviour) or driving a channel the frame does not have, and the problems
  /// above. A behaviour layer's generators are played by a BehaviourPlayer (behaviour_player.hpp):
  /// their values are a function of the show time alone.
  Sampler(const Show& show, std::span<const std::string> frame_channels, std::span<const double> defaults);

  /// Writes every channel of `frame` for show time `show_time_s` (seconds): the defaults, then
  /// the show's tracks over them, then the layers. A looping show wraps the time modulo its
  /// duration (negative times included); a show played once holds its first values before 0 and
  /// its last values after the end (its placements are silent outside their spans). Every value
  /// written is finite. Precondition: frame.size() == frame_size(); a frame of another size is
  /// left untouched. Real-time safe.
  void sample(double show_time_s, std::span<double> frame) noexcept;

  /// Keeps the data of the next samples in cache, one curve per call, in turn over the show's
  /// tracks and the clips' tracks (Curve::warm): the ticks that cross keys, or wrap a looping
  /// show, then do not wait on memory. sample() calls it; a caller that does not sample for a
  /// while (the controller while it homes) calls it each tick instead, so that the first samples
  /// find their data too. Real-time safe, O(1).
  void warm() noexcept;

  std::size_t frame_size() const noexcept { return defaults_.size(); }

 private:
  /// A layer's running sums for one channel it touches.
  struct Slot {
    std::size_t channel = 0;  ///< frame index
    double weighted_sum = 0;
    double weight_sum = 0;
  };
  struct ClipTrack {
    const Curve* curve = nullptr;
    std::size_t slot = 0;  ///< index into slots_
    CurveCursor cursor;
  };
  struct PlacementRun {
    const Placement* placement = nullptr;
    const Clip* clip = nullptr;
    std::size_t first_track = 0, end_track = 0;  ///< range of clip_tracks_
  };
  struct LayerRun {
    const Layer* layer = nullptr;
    std::size_t first_placement = 0, end_placement = 0;  ///< range of placements_
    std::size_t first_slot = 0, end_slot = 0;            ///< range of slots_
    std::size_t behaviour = 0;                           ///< index into behaviours_, for a behaviour layer
  };
  /// A channel a behaviour layer drives: where the generators write it, where the frame has it.
  struct BehaviourChannel {
    std::size_t idle = 0, frame = 0;
    double rest = 0;  ///< the generators move about it; an additive layer adds the motion about it
  };
  struct BehaviourRun {
    BehaviourPlayer player;
    std::vector<double> values;                      ///< the generators' frame (the bound rig's channels)
    std::size_t first_channel = 0, end_channel = 0;  ///< range of behaviour_channels_
  };

  void bind_tracks(std::span<const std::size_t> channel_of_track);
  void bind_layers(std::span<const std::string> frame_channels);
  void bind_behaviour(const Layer& layer, std::span<const std::string> frame_channels, LayerRun& run);
  void compose_layer(LayerRun& run, double t, std::span<double> frame) noexcept;
  void compose_behaviour(const LayerRun& run, double t, std::span<double> frame) noexcept;

  const Show& show_;
  std::vector<std::size_t> channel_of_track_;
  std::vector<double> defaults_;
  std::vector<CurveCursor> cursors_;
  std::vector<LayerRun> layers_;
  std::vector<PlacementRun> placements_;
  std::vector<ClipTrack> clip_tracks_;
  std::vector<Slot> slots_;
  std::vector<BehaviourRun> behaviours_;
  std::vector<BehaviourChannel> behaviour_channels_;
  std::size_t warm_next_ = 0;  ///< the curve warm() reads next: a track, then a clip track
  double warm_sink_ = 0;       ///< what warm() read (kept, so that the reads happen)
};

}  // namespace avar::playback
