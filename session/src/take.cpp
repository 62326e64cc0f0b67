#include "avar/session/take.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/playback/offline/track_fit.hpp"

namespace avar::session {
namespace {

/// A turn sharper than this (degrees) keeps its corner in the fit (CurveFitOptions' default).
constexpr double kCornerAngleDeg = 60;

}  // namespace

TakeReport write_take(const TakeOptions& options, const rig::Rig& rig, const playback::Show& show,
                      const control::Controller& controller, const PlayRecorder& r, const control::LiveInputs& live) {
  if (options.merge && !std::isfinite(show.duration))
    throw std::invalid_argument("a take merges as a layer over a show of finite duration, not over a live-only run; " +
                                options.path + " not written");
  const std::size_t n = rig.channels.size();
  const double start = controller.show_start_time();
  std::vector<double> times;
  std::vector<std::vector<double>> values(n);
  for (std::size_t k = 0; k < r.seconds().size(); ++k) {
    if (r.phase_per_tick()[k] != control::Phase::running) continue;
    times.push_back(r.seconds()[k] - start);
    for (std::size_t c = 0; c < n; ++c) values[c].push_back(r.commands()[k * n + c]);
  }
  // The channels a control moved, and the joints of the targets a control steered.
  std::vector<char> moved(live.touched().begin(), live.touched().end());
  moved.resize(n, 0);
  std::vector<char> steered(n, 0);
  for (std::size_t e = 0; e < live.targets_touched().size() && rig.kinematics; ++e)
    if (live.targets_touched()[e])
      for (const std::size_t b : rig::bindings_moving(*rig.kinematics, e)) steered[rig.kinematics->bindings[b].channel] = 1;
  if (options.merge && rig.kinematics) {
    // A layer plays under the IK: where the show's targets drive a steered joint, the take would
    // not be heard.
    for (const playback::TargetTrack& target : show.targets)
      if (const auto e = rig.kinematics->model.find_effector(target.effector))
        for (const std::size_t b : rig::bindings_moving(*rig.kinematics, *e))
          if (steered[rig.kinematics->bindings[b].channel])
            throw std::invalid_argument("the take steered target '" + target.effector + "', whose joints (channel '" +
                                        rig.channels[rig.kinematics->bindings[b].channel].name +
                                        "' among them) the show's targets drive: a merged layer would be overridden by them; "
                                        "record the take on its own (without merging); " +
                                        options.path + " not written");
  }
  std::vector<std::size_t> performed;
  for (std::size_t c = 0; c < n; ++c)
    if (moved[c] || steered[c]) performed.push_back(c);
  if (times.size() < 2 || !(times.back() > 0) || performed.empty())
    throw std::runtime_error(std::string("nothing to keep: ") +
                             (times.size() < 2 ? "the take ended before the figure ran" : "no control moved a channel") + "; " +
                             options.path + " not written");
  const double duration = times.back();
  const SourceLocation where{options.path, 1, 1};
  std::vector<playback::Track> tracks;
  tracks.reserve(performed.size());
  for (const std::size_t c : performed)
    tracks.push_back(playback::fit_track(rig.channels[c].name, times, values[c], options.tolerance, kCornerAngleDeg, where));

  playback::Show take;
  if (options.merge) {
    take = show;
    playback::Clip clip{"take", duration, playback::ClipMode::hold, std::move(tracks), where};
    take.clips.push_back(std::move(clip));
    playback::Placement placed;
    placed.clip = take.clips.size() - 1;
    placed.end = std::min(duration, take.duration);
    placed.where = where;
    take.layers.push_back({"take", playback::Blend::override, 1.0, {}, {placed}, where, std::nullopt});
  } else {
    take.name = std::filesystem::path(options.path).stem().string();
    take.duration = duration;
    take.tracks = std::move(tracks);
  }
  config::write_show_file(options.path, take, "recorded by avar record on rig '" + rig.name + "'");
  // Read back what was written: the keys that will play, checked against every tick of the take.
  const playback::Show written = config::load_show_file(options.path);
  const std::vector<playback::Track>& kept = options.merge ? written.clips.back().tracks : written.tracks;
  TakeReport report;
  report.duration_s = duration;
  report.ticks = times.size();
  for (std::size_t i = 0; i < kept.size(); ++i)
    report.tracks.push_back(
        {kept[i].channel, kept[i].curve.key_count(), playback::max_fit_error(kept[i].curve, times, values[performed[i]])});
  return report;
}

}  // namespace avar::session
