#pragma once
// Lip sync from a timed sequence of mouth shapes (visemes), offline: every shape is a pose of
// several channels (jaw, lips, cheeks), blended with coarticulation after Cohen and Massaro
// ("Modeling coarticulation in synthetic visual speech", 1993): each segment s has a dominance
//
//   D_s(t) = alpha_s * exp(-d_s(t) / tau),   d_s(t) = how far t lies outside the segment (0 inside),
//   tau = rise_s before the segment (anticipation), decay_s after it (carry-over),
//
// which rises towards the segment and decays after it, and every channel is the dominance-weighted
// average of the segments' poses, F(t) = sum_s D_s(t) T_s / sum_s D_s(t). The distance is taken
// from the segment's extent (Cohen-Massaro measure it from its centre): a long rest then holds
// its pose from its start instead of leaving the previous shape in the mouth until its middle.
// Every value is a convex combination of poses, so it never leaves the range the poses span.
// Load time: allocates, throws std::invalid_argument on broken preconditions.

#include <cstddef>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::playback {

/// One mouth shape held from `start` to `end` (seconds, end >= start).
struct VisemeCue {
  double start = 0;
  double end = 0;
  std::string shape;
  SourceLocation where;  ///< where the cue was read
};

/// Shapes to poses: `poses[i]` holds one value per entry of `channels` (channel units).
struct VisemeTable {
  std::vector<std::string> channels;
  std::vector<std::string> shapes;
  std::vector<std::vector<double>> poses;  ///< [shape][channel]
  std::vector<double> dominance;           ///< alpha of each shape, > 0
  SourceLocation where;

  /// Index of `shape` in shapes, or shapes.size() when the table has no such shape.
  std::size_t find(const std::string& shape) const;
};

struct CoarticulationOptions {
  double rise_s = 0.05;   ///< anticipation time constant, > 0
  double decay_s = 0.05;  ///< carry-over time constant, > 0
  double frame_rate_hz = 100;
};

struct VisemeMotion {
  std::vector<double> times;                ///< seconds, k / frame_rate_hz over [0, end]
  std::vector<std::vector<double>> values;  ///< [channel][frame]
};

/// The blended value of every channel at time t (seconds). Precondition: every cue's shape is in
/// the table (throws std::invalid_argument naming the shape otherwise), cues non-empty.
std::vector<double> blend_visemes_at(const std::vector<VisemeCue>& cues, const VisemeTable& table,
                                     const CoarticulationOptions& options, double t);

/// The blend sampled at frame_rate_hz from 0 to `end_s` (inclusive of the last frame at or before it).
VisemeMotion blend_visemes(const std::vector<VisemeCue>& cues, const VisemeTable& table, const CoarticulationOptions& options,
                           double end_s);

}  // namespace avar::playback
