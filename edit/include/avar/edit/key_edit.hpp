#pragma once
// Edits of one track's keys, as an editor sends them: add keys (a new key, a paste), delete keys,
// move keys in time and value (with their handles), replace a key (its value typed exactly, its
// interpolation, easing, handle types or handles). Keys are named by their index in the track,
// in time order. Each edit is checked whole against the keys it applies to; a key's own fields
// are checked when the curve is built (Curve::build). Load-time code: allocates, throws.

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "avar/playback/runtime/keys.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::edit {

/// An edit that cannot apply: what was asked and why, naming the channel and the key.
class EditError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Inserts keys into `channel`'s track (made when the show has none), each at its own time, in
/// time order. A key within Curve::kKeySnap of another key's time is refused: move or replace
/// that key instead.
struct AddKeys {
  std::string channel;
  std::vector<playback::RawKey> keys;
};

/// Removes keys; removing every key removes the track.
struct DeleteKeys {
  std::string channel;
  std::vector<std::size_t> keys;
};

/// Moves keys by dt seconds and dv channel units, their handles with them. Keys keep their
/// order: a move that would take a key onto or past a key that stays is refused.
struct MoveKeys {
  std::string channel;
  std::vector<std::size_t> keys;
  double dt = 0;
  double dv = 0;
};

/// Replaces one key whole; its time stays strictly between its neighbours'.
struct SetKey {
  std::string channel;
  std::size_t key = 0;
  playback::RawKey value;
};

/// Ripple insert: `length` seconds of nothing at show time `at`; every key, handle, cue and marker at or
/// after `at` (a key within Curve::kKeySnap of it included) moves that much later, on every
/// track, and the show grows by `length`.
struct InsertTime {
  double at = 0;
  double length = 0;
};

/// Ripple delete: the span [from, to) is cut out; keys, cues and markers in it are deleted, those after it
/// move `to - from` earlier on every track, and the show shrinks by the part of the span it had.
struct DeleteTime {
  double from = 0;
  double to = 0;
};

/// Replaces the show's markers whole (add, move, rename and delete are each a new list): each a
/// finite time within the show and a name, not empty and not another's; kept in time order.
struct SetMarkers {
  std::vector<playback::Marker> markers;
};

using KeyEdit = std::variant<AddKeys, DeleteKeys, MoveKeys, SetKey, InsertTime, DeleteTime, SetMarkers>;

/// Whether the edit changes show time (InsertTime, DeleteTime: every track and the cues).
bool is_time_edit(const KeyEdit& edit);

/// The channel a key edit applies to; empty for a time edit (every channel) and SetMarkers (none).
const std::string& edited_channel(const KeyEdit& edit);

/// Where show time `t` goes under a time edit: nullopt when a DeleteTime cuts it out. EditError
/// when the edit itself is malformed (not finite, a length or span not positive).
std::optional<double> rippled_time(double t, const KeyEdit& time_edit);

/// What an edit does, for an undo menu: "move 3 keys of 'jaw' by 0.5 s, +2".
std::string describe(const KeyEdit& edit);

/// `keys` (`channel`'s track, in time order; empty: the channel has no track yet) after `edit`
/// (a key edit of that channel, or a time edit); empty when every key was deleted. Throws
/// EditError: an index out of range or given twice, a non-finite time, value or shift, a key
/// onto another's time, a move or a new time out of order, a malformed time edit.
std::vector<playback::RawKey> edited_keys(const std::vector<playback::RawKey>& keys, const KeyEdit& edit,
                                          const std::string& channel);

}  // namespace avar::edit
