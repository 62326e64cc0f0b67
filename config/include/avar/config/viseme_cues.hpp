#pragma once
// Reading timed mouth shapes (visemes) from lip-sync tools, recognised by their content:
//  - Rhubarb Lip Sync TSV (`rhubarb -f tsv`): one `seconds<TAB>shape` line per cue, each shape
//    held until the next line's time (the last one, usually X, marks the end);
//  - Rhubarb Lip Sync JSON (`rhubarb -f json`): {"mouthCues": [{"start", "end", "value"}, ...]};
//  - Papagayo / Moho switch files (.dat): a `MohoSwitch1` line, then `frame phoneme` lines, frame 1
//    being time 0 at `fps` frames per second, each phoneme held until the next.
// Load time: allocates, throws InputError naming file, line, column (for JSON: the cue's index).

#include <string>
#include <vector>

#include "avar/playback/offline/viseme_blend.hpp"

namespace avar::config {

/// The cues of the file at `path`, sorted by time as written (starts must not decrease),
/// every start >= 0 and end >= start. `fps` (> 0) is used by Moho switch files only. `where`
/// names the option or show key that named the file, for a file that cannot be opened.
std::vector<playback::VisemeCue> read_viseme_cues(const std::string& path, double fps, const SourceLocation& where);

}  // namespace avar::config
