#pragma once
// A jaw track from a sound file: read (libsndfile, mono), the jaw pipeline of
// playback/offline/jaw_from_audio.hpp, then fitted with few Bezier keys (playback::fit_track),
// so the result is an ordinary track that check, feasibility and the limiter treat like any
// other. Shared by `avar jaw` and the show's `audio:` track source. Load time: allocates,
// throws InputError.

#include <string>

#include "avar/core/input_error.hpp"
#include "avar/playback/offline/jaw_from_audio.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::config {

struct JawTrack {
  playback::Track track;       ///< keys within `tolerance` of motion.values at every frame
  playback::JawMotion motion;  ///< the frames fitted, in show time
  double audio_duration_s = 0;
};

/// The default fitting tolerance: 1% of the jaw's travel |open - closed| (channel units).
double default_jaw_tolerance(const playback::JawOptions& options);

/// Reads `audio_path`, runs the jaw pipeline with `options` and fits the frames within
/// `tolerance` (channel units, > 0) as the track of `channel`. The audio starts at `start_s`
/// (show seconds, >= 0; before it the jaw is closed, with a closed key at 0) and frames at or
/// after `end_s` (the show's duration, when the track lives in a show) are left out. Errors
/// (unreadable audio, options out of range) are InputErrors at `where`.
JawTrack jaw_track_from_audio(const std::string& audio_path, const std::string& channel, const playback::JawOptions& options,
                              double tolerance, const SourceLocation& where, double start_s = 0, double end_s = 1e300);

}  // namespace avar::config
