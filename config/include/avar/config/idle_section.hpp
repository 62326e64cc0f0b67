#pragma once
// The `idle:` section of a rig file: which channels get noise, blinks, gaze and breathing, and
// how. Validated whole against the rig's channels (load_rig_file checks it too): every error is
// an InputError naming file:line:col. Values that would leave a channel's range inside its soft
// margins are clipped to it (noise amplitudes, the gaze field); speeds are kept within the
// limits by the generators (playback/runtime/idle_generator.hpp).
//
//   idle:
//     crossfade_s: 0.8                 # hand-over to and from shows and live inputs
//     noise:     {neck_pan: {amplitude: 3, frequency: 0.15, octaves: 2}}
//     blinks:    {lids: {lid_left: {closed: 0}, lid_right: {closed: 0}}, interval_s: [2, 6],
//                 double_probability: 0.15, close_s: 0.08, hold_s: 0.04, open_s: 0.14}
//     gaze:      {eyes: {pan: eyes_pan, tilt: eyes_tilt}, head: {pan: neck_pan, follow: 0.4},
//                 field: {pan: [-20, 20], tilt: [-8, 8]}, fixation_s: [0.4, 2.5]}
//     breathing: {period_s: 4, jitter: 0.1, channels: {neck_tilt: 1.5}}

#include <optional>
#include <string>
#include <vector>

#include "avar/playback/runtime/idle_spec.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

/// The rig's channels' limits as idle life needs them, indexed like rig.channels.
std::vector<playback::IdleChannelLimits> idle_limits(const rig::Rig& rig);

/// Reads the `idle:` section of the rig file at `path` (the file `rig` was loaded from);
/// nullopt when it has none. Throws InputError.
std::optional<playback::IdleSpec> load_idle_section(const rig::Rig& rig, const std::string& path);

}  // namespace avar::config
