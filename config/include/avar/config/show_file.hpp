#pragma once
// Reading a show file (YAML). The whole file is validated before anything can move: every error
// is an InputError naming file, line and column, what was found and what was expected.

#include <string>

#include "avar/playback/runtime/show.hpp"

namespace avar::config {

/// Loads, validates and builds every curve of a show file. Throws InputError on the first
/// problem found.
playback::Show load_show_file(const std::string& path);

/// The same from the text of a show file; `path` names it in errors.
playback::Show load_show_text(const std::string& text, const std::string& path);

/// One key of `channel`'s track from the text of a key map as a show file writes it, in YAML or
/// in JSON ({"time": 1, "value": 2, "interpolation": "bezier", "right": [1.2, 2]}), checked as
/// the show reader checks a key (InputError at `source`:line:col naming the field). in_slope is
/// accepted whatever the key before it.
playback::RawKey load_key_text(const std::string& text, const std::string& channel, const std::string& source);

}  // namespace avar::config
