#pragma once
// Reading a `visemes:` table (shape -> pose of several channels) from a rig or a show file.
// Internal to config/. Load time: throws InputError.

#include <string_view>

#include "yaml_support.hpp"
#include "avar/playback/offline/viseme_blend.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config::detail {

/// `node` is a map shape -> {channel: value, ..., dominance: alpha (> 0, default 1)}; every pose
/// names the same channels as the first.
playback::VisemeTable read_viseme_table(const YamlRef& node, std::string_view what);

/// The rig file's table: read_viseme_table, then every channel one of the rig's and every value
/// within its limits, failing at the offending key or value.
playback::VisemeTable read_rig_viseme_table(const YamlRef& node, const rig::Rig& rig);

}  // namespace avar::config::detail
