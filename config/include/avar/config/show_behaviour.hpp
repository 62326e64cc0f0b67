#pragma once
// Behaviour layers of a show (`behaviour:` on a layer): the rig idle section's generators
// (noise, blinks, gaze, breathing), read by the same reader with the same checks, played over a
// span of the show. Reading a show checks what needs no rig (the behaviour's fields, its span and
// fades, every generator field that does not depend on a channel); the channels, their kinds and
// limits are checked, and the generators bound, against a rig. Load-time only; throws InputError
// naming file:line:col.

#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"

namespace avar::config {

/// Reads every behaviour layer of `show` against `rig` and binds it (LayerBehaviour::idle and
/// channels), so that a Sampler can play it on a frame of the rig's channels. Throws InputError
/// for the first problem (an unknown or digital channel, a value outside a channel's limits...).
void bind_show_behaviour(playback::Show& show, const rig::Rig& rig);

/// Whether the show has a behaviour layer not yet bound to a rig.
bool has_unbound_behaviour(const playback::Show& show);

}  // namespace avar::config
