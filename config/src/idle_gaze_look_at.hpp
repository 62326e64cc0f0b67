#pragma once
// Reading look-at gaze (`look_at:` and `distance:` of an idle gaze section) against the rig's
// kinematics, for read_idle_section.

#include <vector>

#include "avar/playback/runtime/idle_spec.hpp"
#include "avar/rig/rig.hpp"
#include "yaml_support.hpp"

namespace avar::config {

/// Reads `look_at` and `distance` of the gaze `node` into gaze.look_at (and near_probability),
/// the head channels already read: the eye effectors must be the kinematics', hang from one head
/// joint and have revolute joints of their own on deg or rad channels no other idle behaviour
/// drives (`owner`: per channel, the idle behaviour driving it). Computes the gaze frame and the
/// eyes' limits in degrees at the rest pose. Fails (InputError, file:line:col) otherwise.
void read_gaze_look_at(const rig::Rig& rig, const YamlRef& node, playback::GazeSpec& gaze, std::vector<const char*>& owner);

}  // namespace avar::config
