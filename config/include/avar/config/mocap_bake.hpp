#pragma once
// Baking motion capture onto a rig: a mocap file sampled through a retarget map
// (mocap::retarget) and fitted with few Bezier keys per channel and per IK-target axis
// (fit_track, as `avar fit` and `avar record` do), giving a normal show: channel tracks, plus
// position targets the IK stage solves every tick. Shared by `avar mocap bake` (which writes the
// show) and `avar play MOCAPFILE --map MAP` (which plays it from memory). Load time only.

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "avar/mocap/retarget.hpp"
#include "avar/mocap/skeleton_animation.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

struct BakeSettings {
  double tolerance = 0.25;           ///< channel units: keys stay this close to every sample
  double position_tolerance = 1e-3;  ///< metres: target keys stay this close to every sample
  double sample_rate_hz = 0;         ///< 0: the file's own frame rate
  bool clamp = false;                ///< clamp samples outside a channel's limits instead of refusing
  double corner_angle_deg = 60;      ///< see playback::CurveFitOptions
};

struct BakeReport {
  struct Channel {
    std::string name;  ///< channel, or "<target>.x|y|z"
    std::string unit;  ///< the channel's unit, or "m"
    std::size_t samples = 0;
    std::size_t keys = 0;
    double max_error = 0;     ///< largest |show - sample| over the samples
    std::size_t clamped = 0;  ///< samples clamped into the limits (with clamp)
  };
  std::vector<Channel> channels;  ///< tracks first, then target axes
};

/// True for the file names mocap::load_mocap_file reads (.bvh, .gltf, .glb; any case).
bool is_mocap_file(const std::string& path);

/// Reads a motion-capture file by its extension (mocap::load_mocap_file; InputError with the
/// place of a bad file, or naming the path when the extension is not one it reads). Formats
/// without frames of their own (glTF) are sampled at `sample_rate_hz`.
mocap::SkeletonAnimation load_motion_file(const std::string& path, double sample_rate_hz);

struct Baked {
  playback::Show show;
  mocap::RetargetedMotion samples;  ///< what was fitted (clamped into the limits with clamp)
  BakeReport report;
};

/// The show for `animation` through `map` on `rig`: a track per rotation binding, a position
/// target per position binding, fitted within the settings' tolerances; named `name`, lasting
/// the animation's duration. Refuses (InputError at the binding in the map) an animation of one
/// frame, and, unless settings.clamp, a sample outside its channel's limits (the first such
/// sample's time and value). The report's errors are measured on the built curves. `progress`,
/// when not null, gets a line per stage.
Baked bake_show(const mocap::SkeletonAnimation& animation, const mocap::RetargetMap& map, const rig::Rig& rig,
                const BakeSettings& settings, const std::string& name, std::ostream* progress);

/// Sets the max_error of every report entry from `show`'s curves (its tracks, then its targets'
/// x, y, z, in bake order: as bake_show made it or as read back from its file) against `samples`.
void measure_fit(const playback::Show& show, const mocap::RetargetedMotion& samples, BakeReport& report);

/// What `avar play` plays: the show file at `path`, or with `map_path` the motion-capture file at
/// `path` baked in memory through that map (default BakeSettings). Refuses a mocap file without
/// a map and a map with a show file (InputError naming the path).
playback::Show load_playable_show(const std::string& path, const std::optional<std::string>& map_path, const rig::Rig& rig);

}  // namespace avar::config
