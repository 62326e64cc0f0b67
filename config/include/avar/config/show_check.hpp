#pragma once
// Validation of a show against the rig it will play on, before anything moves. Load-time only.

#include <string>
#include <vector>

#include "avar/rig/rig.hpp"
#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config {

struct Finding {
  SourceLocation where;
  std::string message;  ///< what was found and what was expected

  std::string to_string() const;  ///< "file:line:col: message"
};

struct ShowCheck {
  std::vector<Finding> errors;    ///< the show must not play
  std::vector<Finding> warnings;  ///< it may play; the limiter will act
  bool ok() const { return errors.empty(); }
};

/// Errors: a track, a clip's track or a layer's mask naming a channel the rig does not have; a
/// key value of a show track outside its channel's limits (for keys outside the show, before 0 or
/// after its duration, the curve's value where the show starts or ends instead); a channel moved both by a target and
/// by a track (of the show or of a clip a layer places). Warnings: a curve that overshoots the limits between keys (it will be
/// clamped), and rig channels that no track drives (they hold their rest pose). A behaviour
/// layer's generators are read against the rig (show_behaviour.hpp): their problems (unknown or
/// digital channels, values outside a channel's limits...) are errors, with the rig idle
/// section's messages, and the channels they drive count as driven.
ShowCheck check_show_against_rig(const playback::Show& show, const rig::Rig& rig);

}  // namespace avar::config
