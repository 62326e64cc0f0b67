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

}  // namespace avar::config
