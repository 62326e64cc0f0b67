#pragma once
// The show's lip-sync source: `visemes: {file, table, fps, start, rise_ms, decay_ms, tolerance}`
// becomes one fitted track per channel of the table. Internal to config/. Load time: reads the
// cue file, allocates, throws InputError.

#include "yaml_support.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config::detail {

/// Appends the tracks of the `visemes` node to `show` (whose duration is known); a channel that
/// already has a track fails at the table's channel.
void read_show_visemes(const YamlRef& node, playback::Show& show);

}  // namespace avar::config::detail
