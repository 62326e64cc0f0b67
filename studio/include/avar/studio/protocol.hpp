#pragma once
// The studio's protocol (docs/reference/studio-protocol.md): one JSON object per message, with a
// "type". What a client (the studio's page, or any program) sends is parsed here, whole, into a
// session command (play, pause, seek, scrub, loop, hold, release, stop), an e-stop, a group of key
// edits, undo, redo, save, a retime, or a request for the curves or the feasibility check; channels are named and resolved
// against the rig's. Keys in edits are the show file's key maps written in JSON, checked by the show reader's own rules. Pure: no
// I/O. Not real-time: allocates and throws.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "avar/edit/key_edit.hpp"
#include "avar/session/command_queue.hpp"

namespace avar::studio {

/// A message that cannot be taken: which message, which field, what was found and expected.
class ProtocolError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct Estop {};
struct Edit {
  std::vector<edit::KeyEdit> edits;  ///< one undo step, applied all or nothing
  bool continues = false;            ///< the next move of a drag: ShowDocument::continue_last
};
struct Undo {};
struct Redo {};
struct Save {};
/// The show's tracks as the curve engine's flat keys (raw_curve_codec.hpp), for a client that
/// evaluates curves itself (the page's WebAssembly engine): every track, or those of `channels`.
struct Curves {
  std::optional<std::vector<std::string>> channels;  ///< rig channels, checked
};

/// What the show asks of the rig beyond its limits (config::check_feasibility), for the page's
/// timeline.
struct Check {};
/// Stretch what asks too much to the rig's limits (edit::ShowDocument::retime): one undo step.
struct Retime {};
/// The outline of the sound each track made from audio follows (a jaw's voice), for drawing.
struct Waveform {};
using ClientMessage = std::variant<session::Command, Estop, Edit, Undo, Redo, Save, Curves, Check, Retime, Waveform>;

/// Parses one message. `channels`: the rig's channel names, in the rig's order (a hold's channel
/// index is its place there; an edit may name only these). `targets`: the show's targets' names
/// (their effectors), in the show's order (an aim's index is the place there). Throws ProtocolError: not JSON, not
/// an object, an unknown type or field, a missing field, a field of the wrong kind, a number that
/// is not finite, an unknown channel, a key the show reader refuses (its words).
ClientMessage parse_client_message(std::string_view text, const std::vector<std::string>& channels,
                                   const std::vector<std::string>& targets = {});

}  // namespace avar::studio
