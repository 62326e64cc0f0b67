#pragma once
// Writing a show file (YAML) that load_show_file reads back to the same curves: every key field,
// handle type, easing parameter, extrapolation and Cycles setting, and the targets, each written
// only where its interpolation uses it. Load time only.

#include <cstddef>
#include <string>

#include "avar/playback/runtime/show.hpp"

namespace avar::config {

/// The show file's text: `comment` as the first line (after "# "), then the show. OSC cues are
/// written as cues; digital cues as the step tracks the reader made of them.
std::string show_text(const playback::Show& show, const std::string& comment);

/// The show as one JSON object with the show file's fields (name, duration, loop, tracks with
/// their keys, targets, clips, layers, cues), as show_text writes them; numbers round-trip.
std::string show_json(const playback::Show& show);

/// Keys [from, from + count) of `raw` as a JSON array, each as show_json writes it in its track
/// (the key before `from` decides whether a key writes its in_slope). from + count <= the keys.
std::string keys_json(const playback::RawCurve& raw, std::size_t from, std::size_t count);

/// Writes `show` to `path`, with `comment` as the first line (after "# "). Throws InputError
/// naming the path when it cannot be written.
void write_show_file(const std::string& path, const playback::Show& show, const std::string& comment);

}  // namespace avar::config
