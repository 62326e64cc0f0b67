#pragma once
// Reading a layer's `behaviour:` map (show_behaviour.hpp in include/), for the show reader, and
// checking it against a rig, for check_show_against_rig.

#include <string>
#include <vector>

#include "avar/config/show_check.hpp"
#include "avar/playback/runtime/show.hpp"
#include "yaml_support.hpp"

namespace avar::config::detail {

/// The behaviour of layer `layer` of `show` (whose duration is known): its seed, span and fades,
/// and its generators' text (checked without a rig as far as that goes). Throws InputError.
playback::LayerBehaviour read_behaviour(const YamlRef& node, const playback::Show& show, const std::string& layer);

/// The keys of a behaviour that its generators read, in the order the writer writes them.
extern const char* const kBehaviourGenerators[4];

/// The generators' part of a behaviour read from a show file (noise, blinks, gaze, breathing, as
/// written), for the show writer; nullptr for one not read from a file.
const YAML::Node* behaviour_text(const playback::LayerBehaviour& behaviour);

/// Adds the problems of a behaviour layer's generators on this rig to `errors`, and marks the
/// channels they drive (where the layer's mask lets them) in `driven`.
void check_behaviour(const playback::Layer& layer, const rig::Rig& rig, std::vector<bool>& driven, std::vector<Finding>& errors);

}  // namespace avar::config::detail
