#pragma once
// A show being edited: its tracks' keys changed by key edits (key_edit.hpp), every change one
// step of an undo history, saved to a show file. What the studio's server holds for the page.
//
//   ShowDocument doc = ShowDocument::open("show.yaml");
//   doc.apply(MoveKeys{"jaw", {2, 3}, 0.1, 0});   // validated whole; one undo step
//   doc.apply({edit_a, edit_b});                   // a group (a box selection): one step
//   doc.undo(); doc.redo();
//   doc.save("show.yaml");
//
// Time edits (ripple insert and delete) move every track's keys and the cues, and change the
// duration; a show with layers or targets refuses them (their times would be left behind).
//
// An edit is checked whole (the edit itself, then every changed curve built as playback builds
// it) before anything changes: a refused edit leaves the show, the history and the saved state
// as they were. The show's curves are always the built form of its keys, ready to sample.
//
// Saving: the show as it was opened (no edit, or every edit undone) writes the file's own bytes
// again, comments and layout included; any other state writes the show writer's canonical form,
// which the show reader reads back to the same curves. So open, save writes the same bytes, and
// edits undone to the start save the original file.
//
// Threads: one at a time (the server's thread). Not real-time: allocates and throws.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "avar/edit/key_edit.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"

namespace avar::edit {

/// Where a track's keys changed: keys [from, from + removed) of the track before became keys
/// [from, from + added) after; the keys before and after that stretch are the same (and written
/// the same: a key's written form depends on the key before it, so the stretch takes the key
/// after a changed one with it).
struct KeySplice {
  std::string channel;
  std::size_t from = 0, removed = 0, added = 0;
};

/// What one change of the document changed, for someone who holds a copy of the show: the
/// splices of existing tracks' keys, or `whole` when more changed (a track made or removed, the
/// duration or the cues) and only the whole show tells.
struct DocumentChange {
  bool whole = false;
  std::vector<KeySplice> splices;
};

class ShowDocument {
 public:
  /// A show made in memory: saving always writes the canonical form.
  explicit ShowDocument(playback::Show show);
  /// Reads and checks the show file whole (load_show_file's InputError, file:line:col) and keeps
  /// its bytes for an unchanged save.
  static ShowDocument open(const std::string& path);

  const playback::Show& show() const noexcept { return show_; }

  /// Applies one edit, or a group of edits in order, as one undo step; EditError (nothing
  /// changed) when any of them cannot apply or a changed curve would not build. Applying after
  /// an undo drops the steps that could have been redone.
  void apply(const KeyEdit& edit);
  void apply(std::span<const KeyEdit> edits);
  void apply(std::initializer_list<KeyEdit> edits) { apply(std::span<const KeyEdit>(edits.begin(), edits.size())); }
  /// The same, continuing the last step (the next pointer move of a drag): the last step then
  /// goes from before the drag to after this move, so a whole drag is one undo step and the
  /// history does not grow with it. It continues only when the last step is the newest, was not
  /// saved since, and both change the keys of existing tracks only, the same tracks; otherwise
  /// this is a step of its own.
  void continue_last(std::span<const KeyEdit> edits);
  void continue_last(std::initializer_list<KeyEdit> edits) {
    continue_last(std::span<const KeyEdit>(edits.begin(), edits.size()));
  }

  /// Stretches the spans that ask more speed or acceleration than `rig`'s channels allow
  /// (config::retime: every track alike, later keys and cues moved by the added time), as one
  /// undo step. EditError, nothing changed, when no span asks too much, or the show has layers or
  /// targets (whose times a stretch would leave behind).
  void retime(const rig::Rig& rig);

  /// Steps back or forward one undo step; false when there is none.
  bool undo();
  bool redo();
  std::size_t undo_steps() const noexcept { return position_; }
  std::size_t redo_steps() const noexcept { return history_.size() - position_; }
  /// What undo() or redo() would do ("move 2 keys of 'jaw' by 0.1 s, +0"); empty when nothing.
  std::string undo_label() const;
  std::string redo_label() const;

  /// What the last apply, continue_last, retime, undo or redo changed (nothing before the first,
  /// and after a refused edit).
  const DocumentChange& last_change() const noexcept { return last_change_; }

  /// Whether the show differs from what was last saved (or opened).
  bool modified() const noexcept { return !saved_position_ || *saved_position_ != position_; }

  /// Writes the show to `path` (see the file comment) and makes this state the saved one.
  /// InputError naming the path when it cannot be written.
  void save(const std::string& path);

 private:
  /// One track's keys before and after a step; nullopt: no track (made or removed by the step).
  struct TrackChange {
    std::string channel;
    std::size_t position = 0;  ///< the track's index in show_.tracks while it exists
    std::optional<playback::RawCurve> before, after;
  };
  /// What a time edit changes besides the tracks.
  struct Times {
    double duration = 0;
    std::vector<playback::Cue> cues;
    std::vector<playback::Marker> markers;
  };
  /// The markers an edit sets, checked against the show's duration and sorted (EditError).
  static std::vector<playback::Marker> checked_markers(const SetMarkers& edit, double duration);
  struct Step {
    std::string label;
    std::vector<TrackChange> changes;
    std::optional<Times> times_before, times_after;  ///< set by a step with a time edit
  };

  /// Puts `raw` as `channel`'s track at `position` (its curve `built` already, or built here), or
  /// removes the track.
  void put(const TrackChange& change, const std::optional<playback::RawCurve>& raw,
           std::optional<playback::Curve> built = std::nullopt);
  void put(const std::optional<Times>& times);
  /// The duration and cues after `edit`; EditError when the show would have no time left or has
  /// parts a time edit does not move (layers, targets).
  Times rippled(const Times& times, const KeyEdit& edit) const;
  std::optional<std::size_t> track_of(const std::string& channel) const;
  void apply(std::span<const KeyEdit> edits, bool continuing);
  /// Makes `step` (applied already) the newest undo step, dropping what could have been redone.
  void push_step(Step step);
  /// Whether `step` may be folded into the last step (see continue_last).
  bool continues_last(const Step& step) const;

  playback::Show show_;
  DocumentChange last_change_;
  std::optional<std::string> opened_bytes_;  ///< the file as opened, for a save of that state
  std::vector<Step> history_;
  std::size_t position_ = 0;                       ///< steps applied; history_[position_ - 1] was the last
  std::optional<std::size_t> saved_position_ = 0;  ///< nullopt: the saved state is no longer in the history
};

}  // namespace avar::edit
