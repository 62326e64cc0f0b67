#include "avar/playback/offline/track_fit.hpp"

#include <algorithm>
#include <cmath>

#include "avar/playback/offline/curve_fit.hpp"

namespace avar::playback {

Track fit_track(const std::string& channel, std::span<const double> times, std::span<const double> values, double tolerance,
                double corner_angle_deg, const SourceLocation& where) {
  CurveFitOptions fit_options;
  // A hair inside the tolerance, so that the written decimal numbers cannot push a sample over.
  fit_options.tolerance = tolerance * (1 - 1e-9);
  fit_options.corner_angle_deg = corner_angle_deg;
  Track track;
  track.channel = channel;
  track.where = where;
  track.raw = fit_curve(times, values, fit_options, where).curve;
  track.curve = Curve::build(track.raw);
  return track;
}

double max_fit_error(const Curve& curve, std::span<const double> times, std::span<const double> values) {
  double worst = 0;
  CurveCursor cursor;
  for (std::size_t i = 0; i < times.size(); ++i) worst = std::max(worst, std::abs(curve.evaluate(times[i], cursor) - values[i]));
  return worst;
}

void keep_handles_within(Track& track, double lo, double hi) {
  for (auto& key : track.raw.keys)
    for (auto* handle : {&key.left, &key.right})
      if (*handle) (*handle)->value = std::clamp((*handle)->value, lo, hi);
  track.curve = Curve::build(track.raw);
}

}  // namespace avar::playback
