#pragma once
// Reading a rig file's `idle:` node (idle_section.hpp), for load_rig_file's whole-file check,
// and the same generators in a show's behaviour layer (show_behaviour.cpp).

#include "avar/playback/runtime/idle_spec.hpp"
#include "avar/rig/rig.hpp"
#include "yaml_support.hpp"

namespace avar::config {

playback::IdleSpec read_idle_section(const rig::Rig& rig, const YamlRef& node);

/// The generators of an idle section or a show's behaviour layer (noise, blinks, gaze,
/// breathing) in `node`, a map whose keys the caller has checked, into spec (with the rig's
/// limits); `what` names the map in errors ("idle"). Throws InputError.
void read_idle_generators(const rig::Rig& rig, const YamlRef& node, const std::string& what, playback::IdleSpec& spec);

}  // namespace avar::config
