#pragma once
// Reading a rig file's `idle:` node (idle_section.hpp), for load_rig_file's whole-file check.

#include "avar/playback/runtime/idle_spec.hpp"
#include "avar/rig/rig.hpp"
#include "yaml_support.hpp"

namespace avar::config {

playback::IdleSpec read_idle_section(const rig::Rig& rig, const YamlRef& node);

}  // namespace avar::config
