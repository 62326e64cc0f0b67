#pragma once
// One channel's samples fitted with few Bezier keys (fit_curve) as a track of a show: shared by
// `avar fit` (samples from a CSV), `avar record` (a live take), `avar jaw` and the show's audio
// and viseme track sources. Offline: allocates.

#include <span>
#include <string>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::playback {

/// The track of `channel` through samples (times strictly increasing, seconds) within
/// `tolerance` (channel units, > 0) of every sample, as written to a file and read back.
Track fit_track(const std::string& channel, std::span<const double> times, std::span<const double> values, double tolerance,
                double corner_angle_deg, const SourceLocation& where);

/// The largest |curve(t_i) - v_i| over the samples.
double max_fit_error(const Curve& curve, std::span<const double> times, std::span<const double> values);

/// Moves every handle value of the track's keys into [lo, hi] and rebuilds its curve. A Bezier
/// segment stays inside the hull of its control points (time runs monotonically in fitted
/// segments), so with its keys inside [lo, hi] the curve never leaves it.
void keep_handles_within(Track& track, double lo, double hi);

}  // namespace avar::playback
