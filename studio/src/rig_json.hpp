#pragma once
// The rig as the studio's hello describes it (docs/reference/studio-protocol.md): channels and
// their limits, links, the kinematic tree for the page's 3-D view, and the curve vocabulary for
// its menus. Internal to the studio: nlohmann_json stays out of the public headers.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "avar/rig/rig.hpp"

namespace avar::studio {

/// A measurement that may be missing (NaN): null then.
inline nlohmann::json maybe(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); }

/// `{name, rate_hz, channels, links, kinematics}`; kinematics is null for a rig without one.
nlohmann::json rig_json(const rig::Rig& rig);

/// A mesh file's format as the page loads it, from its extension: "stl", "dae", "obj", or
/// "unknown".
std::string mesh_format(const std::string& path);

/// `{interpolations, easings, handle_types, extrapolations}`: the show file's names, in order.
nlohmann::json curve_vocabulary_json();

}  // namespace avar::studio
