#pragma once
// Lip-sync tracks: timed mouth shapes (config/viseme_cues.hpp) blended with coarticulation
// (playback/offline/viseme_blend.hpp) through a `visemes:` table of poses, sampled and fitted
// with few Bezier keys per channel. Shared by `avar visemes` and the show's `visemes:` source.
// Load time: allocates, throws InputError.

#include <optional>
#include <string>
#include <vector>

#include "avar/playback/offline/viseme_blend.hpp"
#include "avar/playback/runtime/track.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

/// One track per table channel over show time [0, end_s]: the cues shifted by `start_s`,
/// blended and sampled at options.frame_rate_hz, fitted within `tolerance` (default: 1% of the
/// span of the channel's poses) and kept inside the span of its poses. Every cue's shape must be
/// in the table (InputError at the cue otherwise). When the table has a rest shape (`X`, as
/// Rhubarb names it, or `rest`, as Papagayo does), it holds before the first cue and after the last.
std::vector<playback::Track> viseme_tracks(const std::vector<playback::VisemeCue>& cues, const playback::VisemeTable& table,
                                           const playback::CoarticulationOptions& options, double start_s, double end_s,
                                           std::optional<double> tolerance, const SourceLocation& where);

/// The rig file's optional `visemes:` table (shape: {channel: value, ..., dominance: alpha}),
/// every channel one of the rig's and every value within its limits; nullopt when the rig file
/// has none. Throws InputError at file:line:col.
std::optional<playback::VisemeTable> load_rig_visemes(const std::string& rig_path, const rig::Rig& rig);

}  // namespace avar::config
