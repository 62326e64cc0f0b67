#pragma once
// Reading a rig file (YAML). The whole file is validated before anything can move: every error
// is an InputError naming file, line and column, what was found and what was expected.

#include <string>

#include "avar/rig/rig.hpp"

namespace avar::config {

/// Loads and validates a rig file. Throws InputError on the first problem found.
rig::Rig load_rig_file(const std::string& path);

/// The same from the text of a rig file; `path` names it in errors, and relative paths in it (a
/// URDF file) are relative to its folder.
rig::Rig load_rig_text(const std::string& text, const std::string& path);

}  // namespace avar::config
