#include "avar/config/viseme_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/playback/offline/track_fit.hpp"
#include "viseme_table.hpp"

namespace avar::config {

std::vector<playback::Track> viseme_tracks(const std::vector<playback::VisemeCue>& cues, const playback::VisemeTable& table,
                                           const playback::CoarticulationOptions& options, double start_s, double end_s,
                                           std::optional<double> tolerance, const SourceLocation& where) {
  if (cues.empty()) throw InputError(where, "found no mouth cues; expected at least one");
  std::vector<playback::VisemeCue> shifted = cues;
  for (auto& cue : shifted) {
    if (table.find(cue.shape) == table.shapes.size()) {
      std::string known;
      for (const auto& s : table.shapes) known += (known.empty() ? "" : ", ") + s;
      throw InputError(cue.where, "mouth shape '" + cue.shape + "' is not in the visemes table; expected one of: " + known);
    }
    cue.start += start_s;
    cue.end += start_s;
  }
  // The rest shape, when the table has one, holds the mouth before the first cue and after the
  // last (else the nearest cues' mixture would).
  const std::size_t rest = table.find("X") != table.shapes.size() ? table.find("X") : table.find("rest");
  if (rest != table.shapes.size()) {
    playback::VisemeCue before;
    before.shape = table.shapes[rest];
    before.where = where;
    playback::VisemeCue after = before;
    before.end = shifted.front().start;
    after.start = shifted.back().end;
    after.end = std::max(after.start, end_s);
    if (before.end > 0) shifted.insert(shifted.begin(), before);
    if (after.end > after.start) shifted.push_back(after);
  }
  playback::VisemeMotion motion;
  try {
    motion = playback::blend_visemes(shifted, table, options, end_s);
  } catch (const std::invalid_argument& e) {
    throw InputError(where, e.what());
  }
  std::vector<playback::Track> tracks;
  tracks.reserve(table.channels.size());
  for (std::size_t c = 0; c < table.channels.size(); ++c) {
    double lo = table.poses[0][c], hi = lo;
    for (const auto& pose : table.poses) {
      lo = std::min(lo, pose[c]);
      hi = std::max(hi, pose[c]);
    }
    const double tol = tolerance.value_or(std::max(0.01 * (hi - lo), 1e-6));
    if (motion.times.size() == 1) motion.values[c][0] = std::clamp(motion.values[c][0], lo, hi);
    playback::Track track = playback::fit_track(table.channels[c], motion.times, motion.values[c], tol, 60, where);
    playback::keep_handles_within(track, lo, hi);
    tracks.push_back(std::move(track));
  }
  return tracks;
}

std::optional<playback::VisemeTable> load_rig_visemes(const std::string& rig_path, const rig::Rig& rig) {
  const YAML::Node root = load_yaml_file(rig_path);
  const auto node = YamlRef{root, &rig_path}.find("visemes");
  if (!node) return std::nullopt;
  return detail::read_rig_viseme_table(*node, rig);
}

}  // namespace avar::config
