#pragma once
// A show track whose keys come from a voice recording: `<channel>: {audio: {file, open, ...}}`.
// Internal to config/. Load time: reads the sound file, allocates, throws InputError.

#include <string>

#include "yaml_support.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::config::detail {

/// `audio` is the map {file (relative to the show file), open, closed, start, lead_ms, gate_db,
/// full_db, hysteresis_db, attack_ms, release_ms, band_hz: [lo, hi], curve, tolerance}; the
/// track of `channel` (named at `name`) is fitted from it (config/jaw_track.hpp) and cut at the
/// show's `duration`.
playback::Track read_audio_track(const YamlRef& name, const YamlRef& audio, double duration);

}  // namespace avar::config::detail
