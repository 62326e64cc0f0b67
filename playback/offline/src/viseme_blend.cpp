#include "avar/playback/offline/viseme_blend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace avar::playback {

std::size_t VisemeTable::find(const std::string& shape) const {
  return static_cast<std::size_t>(std::find(shapes.begin(), shapes.end(), shape) - shapes.begin());
}

std::vector<double> blend_visemes_at(const std::vector<VisemeCue>& cues, const VisemeTable& table, const CoarticulationOptions& o,
                                     double t) {
  if (cues.empty()) throw std::invalid_argument("visemes: no cues to blend");
  if (!(o.rise_s > 0) || !(o.decay_s > 0)) throw std::invalid_argument("visemes: rise and decay must be above 0 s");
  // Log-dominances, so that cues far away (exp underflow) still weigh in exactly when nothing
  // nearer does: weights are exp(log D - max log D).
  std::vector<double> log_d(cues.size());
  std::vector<std::size_t> pose(cues.size());
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < cues.size(); ++s) {
    pose[s] = table.find(cues[s].shape);
    if (pose[s] == table.shapes.size()) throw std::invalid_argument("visemes: shape '" + cues[s].shape + "' is not in the table");
    const double before = cues[s].start - t, after = t - cues[s].end;
    const double outside = before > 0 ? before / o.rise_s : after > 0 ? after / o.decay_s : 0;
    log_d[s] = std::log(table.dominance[pose[s]]) - outside;
    top = std::max(top, log_d[s]);
  }
  std::vector<double> value(table.channels.size(), 0.0);
  double total = 0;
  for (std::size_t s = 0; s < cues.size(); ++s) {
    const double w = std::exp(log_d[s] - top);
    total += w;
    for (std::size_t c = 0; c < value.size(); ++c) value[c] += w * table.poses[pose[s]][c];
  }
  for (double& v : value) v /= total;
  return value;
}

VisemeMotion blend_visemes(const std::vector<VisemeCue>& cues, const VisemeTable& table, const CoarticulationOptions& o,
                           double end_s) {
  if (!(o.frame_rate_hz > 0)) throw std::invalid_argument("visemes: the frame rate must be above 0 Hz");
  VisemeMotion motion;
  motion.values.resize(table.channels.size());
  const auto frames = static_cast<std::size_t>(std::floor(std::max(end_s, 0.0) * o.frame_rate_hz + 1e-9)) + 1;
  motion.times.reserve(frames);
  for (auto& channel : motion.values) channel.reserve(frames);
  for (std::size_t k = 0; k < frames; ++k) {
    const double t = static_cast<double>(k) / o.frame_rate_hz;
    motion.times.push_back(t);
    const std::vector<double> v = blend_visemes_at(cues, table, o, t);
    for (std::size_t c = 0; c < v.size(); ++c) motion.values[c].push_back(v[c]);
  }
  return motion;
}

}  // namespace avar::playback
