#pragma once
// Reading a retarget map (YAML): which joints of a motion-capture file drive which channels and
// IK targets of a rig (the format is in the README, "Retargeting motion capture"; the maths in
// avar/mocap/retarget.hpp). Validated whole against the rig before anything moves: every error
// is an InputError naming file, line and column, what was found and what was expected. The
// joint names are checked against the animation later, by mocap::retarget, at their place in
// the map. Load time only.

#include <string>

#include "avar/mocap/retarget.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

/// Loads and validates `path` against `rig`: channels the rig has (analog, each bound once, not
/// moved by a mapped IK target), effectors of its kinematics (each bound once), Euler axes and
/// orders, angle units matching a deg or rad channel's, axis mappings that use every file axis
/// once, finite numbers. Throws InputError on the first problem.
mocap::RetargetMap load_retarget_map(const std::string& path, const rig::Rig& rig);

}  // namespace avar::config
