#pragma once
// Reading the `cues:` and `markers:` of a show file. Internal to config/. Load time: allocates, throws
// InputError at the offending entry.

#include "yaml_support.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config::detail {

/// Reads the list into show.cues (sorted by time) and turns each digital channel's cues into a
/// step track of that channel (off before its first cue). Needs show.duration and show.tracks.
void read_cues(const YamlRef& list, playback::Show& show);

/// Reads `markers:` ({time, name} each) into show.markers, sorted by time: a time within the
/// show (needs show.duration), a name that is not empty and not another marker's.
void read_markers(const YamlRef& list, playback::Show& show);

}  // namespace avar::config::detail
