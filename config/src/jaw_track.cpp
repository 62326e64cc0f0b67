#include "avar/config/jaw_track.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "avar/config/audio_file.hpp"
#include "avar/playback/offline/track_fit.hpp"

namespace avar::config {
namespace {

/// Bezier segments stay inside the hull of their control points: with every handle value inside
/// [closed, open] the curve never leaves the jaw's travel, and a segment between two closed keys
/// over closed frames (silence) with its handles at closed stays exactly closed.
void keep_inside_travel(playback::Track& track, const playback::JawMotion& m, const playback::JawOptions& o) {
  auto& keys = track.raw.keys;
  std::size_t frame = 0;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (keys[i].value != o.closed || keys[i + 1].value != o.closed) continue;
    while (frame < m.times.size() && m.times[frame] < keys[i].time) ++frame;
    bool silent = true;
    for (std::size_t f = frame; f < m.times.size() && m.times[f] <= keys[i + 1].time; ++f)
      silent = silent && m.values[f] == o.closed;
    if (!silent) continue;
    if (keys[i].right) keys[i].right->value = o.closed;
    if (keys[i + 1].left) keys[i + 1].left->value = o.closed;
  }
  playback::keep_handles_within(track, std::min(o.closed, o.open), std::max(o.closed, o.open));
}

}  // namespace

double default_jaw_tolerance(const playback::JawOptions& options) {
  return std::max(0.01 * std::abs(options.open - options.closed), 1e-6);
}

JawTrack jaw_track_from_audio(const std::string& audio_path, const std::string& channel, const playback::JawOptions& options,
                              double tolerance, const SourceLocation& where, double start_s, double end_s) {
  try {
    playback::validate(options);
  } catch (const std::invalid_argument& e) {
    throw InputError(where, std::string("jaw options: ") + e.what());
  }
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw InputError(where, "expected a fitting tolerance above 0 (channel units), found " + std::to_string(tolerance));
  if (!(start_s >= 0) || !(start_s < end_s))
    throw InputError(where, "expected the audio to start within the show, at 0 s or later");
  const MonoAudio audio = read_mono_audio(audio_path, where);
  JawTrack result;
  result.audio_duration_s = audio.duration_s();
  try {
    result.motion = playback::jaw_from_audio(audio.samples, audio.sample_rate_hz, options);
  } catch (const std::invalid_argument& e) {
    throw InputError(where, "audio file '" + audio_path + "': " + e.what());
  }
  auto& m = result.motion;
  for (double& t : m.times) t += start_s;
  const auto kept = static_cast<std::size_t>(std::lower_bound(m.times.begin(), m.times.end(), end_s) - m.times.begin());
  m.times.resize(std::max<std::size_t>(kept, 1));
  m.values.resize(m.times.size());
  m.envelope_db.resize(m.times.size());
  if (start_s > 0) {
    // Closed frames before the audio, so that the fit holds the jaw there too.
    std::vector<double> before;
    for (std::size_t k = 0; static_cast<double>(k) / options.frame_rate_hz < start_s - 1e-9; ++k)
      before.push_back(static_cast<double>(k) / options.frame_rate_hz);
    m.times.insert(m.times.begin(), before.begin(), before.end());
    m.values.insert(m.values.begin(), before.size(), options.closed);
    m.envelope_db.insert(m.envelope_db.begin(), before.size(), -200.0);
  }
  result.track = playback::fit_track(channel, m.times, m.values, tolerance, 60, where);
  keep_inside_travel(result.track, m, options);
  return result;
}

}  // namespace avar::config
