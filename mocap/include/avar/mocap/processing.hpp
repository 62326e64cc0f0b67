#pragma once
// Processing of a skeleton animation before retargeting: resampling, trimming, smoothing and
// loop detection. Each returns a new animation (same joints, channels and source) and leaves its
// input alone. Load time only: allocates; throws std::invalid_argument for bad arguments.

#include <cstddef>

#include "avar/mocap/skeleton_animation.hpp"
#include "avar/playback/offline/smoothing.hpp"

namespace avar::mocap {

/// The animation sampled by evaluate() at i / rate_hz seconds, i = 0 .. while i / rate_hz <=
/// duration() (the last sample may fall short of the end by less than a frame). rate_hz > 0.
SkeletonAnimation resample(const SkeletonAnimation& animation, double rate_hz);

/// The part from `from_s` to `to_s` (seconds, clamped to [0, duration()], from_s <= to_s),
/// sampled by evaluate() at from_s + i * frame_time; time 0 of the result is from_s.
SkeletonAnimation trim(const SkeletonAnimation& animation, double from_s, double to_s);

/// Smooths every joint's motion with a playback filter at `cutoff_hz` (in (0, rate / 2), rate =
/// 1 / frame_time): translations and scales per component; rotations quaternion-aware, with
/// successive quaternions first brought into one hemisphere (so no filter runs across a q / -q
/// flip), then each component filtered and the result renormalised.
SkeletonAnimation smooth(const SkeletonAnimation& animation, playback::SmoothingMethod method, double cutoff_hz);

/// Distance between the poses of frames `first` and `second`: the root-mean-square over joints of
/// the angle (radians) between their local rotations. Translations are left out (a walk's root
/// travels).
double pose_distance(const SkeletonAnimation& animation, std::size_t first, std::size_t second);

struct LoopMatch {
  std::size_t first = 0;  ///< frame the loop starts at
  std::size_t last = 0;   ///< frame whose pose best matches `first` (play first .. last - 1, repeat)
  double distance = 0;    ///< pose_distance(first, last)
};

/// The frame pair at least `min_length_s` apart whose poses match best (smallest
/// pose_distance; ties: the earliest, then the longest). Costs O(frames^2 * joints).
/// Throws when no pair is that far apart.
LoopMatch find_loop(const SkeletonAnimation& animation, double min_length_s);

}  // namespace avar::mocap
