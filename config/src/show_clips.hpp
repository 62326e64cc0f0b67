#pragma once
// Reading the clips and layers of a show file (playback/timeline.hpp). Internal to config/.
// Load time: allocates, throws InputError naming file, line and column.

#include "yaml_support.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config::detail {

/// `clips: {name: {duration, mode, tracks}}` and `layers: [{name, blend, weight, channels,
/// clips: [placements]}]` of the show file `root`, into `show`, whose duration is already read.
/// Clips without layers are refused (nothing would play them).
void read_clips_and_layers(const YamlRef& root, playback::Show& show);

}  // namespace avar::config::detail
