#pragma once
// The `kinematics:` section of a rig file: a joint tree (revolute, prismatic and fixed joints
// with parent, axis, origin and the channel that drives each movable joint) and named effectors.
// Validated whole at load: unknown parents, cycles, zero axes, unknown joint types, movable joints
// without a channel, channels without a known unit and no scale, are InputErrors naming file,
// line and what was expected. Load time only.

#include "yaml_support.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

/// Reads the section; `rig` must already hold its channels (joints bind to them by name).
rig::RigKinematics read_rig_kinematics(const rig::Rig& rig, const YamlRef& node);

}  // namespace avar::config
