#pragma once
// The studio's side of the conversation (docs/reference/studio-protocol.md), apart from any
// transport: a client's message goes in as text, the replies come out as text, one for the client
// that sent it and others for every client. The show being edited (edit::ShowDocument) is the
// studio's own; every change to it is handed to the running session (ShowSession::replace_show),
// so the figure follows the edit at once. The session's tick records come in as an observer and
// go out as status messages.
//
// Threads: handle(), hello() and take_status() from any thread (serialised inside); on_tick()
// on the session's publisher thread. Not real-time: allocates and throws.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "avar/edit/show_document.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"
#include "avar/session/show_session.hpp"
#include "avar/session/tick_record.hpp"

namespace avar::studio {

/// What a message makes the studio say: to the client that sent it, and to every client.
struct Replies {
  std::string to_sender;            ///< "ok", "error" or "saved"
  std::vector<std::string> to_all;  ///< "keys" or "show" after a change of the show
};

class Studio final : public session::SessionObserver {
 public:
  /// `document` is the show being edited (validated against `rig`, borrowed), saved to
  /// `show_path` (empty: the show has no file, and save is refused).
  Studio(const rig::Rig& rig, edit::ShowDocument document, std::string show_path);

  /// The show the figure's session must be made with: a copy of the document's, which the
  /// studio keeps alive (the document's own show changes under edits).
  const playback::Show& initial_show() const noexcept { return *initial_; }
  /// The session that plays initial_show() (borrowed; outlives the studio, or is detached with
  /// nullptr). Until then commands are refused; edits change the document alone.
  void attach(session::ShowSession* session);

  /// The first message to a client that connects: the rig's channels, the show, the file, and
  /// the undo state.
  std::string hello() const;
  /// Takes one client message whole (ProtocolError and refused edits become an "error" reply;
  /// nothing changes then).
  Replies handle(std::string_view message);
  /// The newest tick as a "status" message, when a tick came since the last call; and, first,
  /// one "refused" message per command the session refused since.
  std::vector<std::string> take_status();
  /// The newest tick as a "status" message, whether or not it was taken (phase "disabled" and
  /// no channels before the first tick).
  std::string status();
  /// The file of the rig's visual `index` (the hello's kinematics.visuals, mesh url
  /// /api/mesh/INDEX) when it is a mesh whose file exists; nullopt otherwise. Any thread.
  std::optional<std::string> mesh_file(std::size_t index) const;

  /// Publisher thread: keeps the newest record.
  void on_tick(const session::TickRecord& record) override;

  const edit::ShowDocument& document() const noexcept { return document_; }

 private:
  /// What every message about the show says of its state (version, file, modified, undo, redo),
  /// as a JSON object's text without its braces.
  std::string state_fields() const;
  /// The show's fields of a "show" or "hello" message, without braces.
  std::string show_fields() const;
  std::string show_message() const;
  /// What every client is told after the document changed: "keys" with the stretches of keys
  /// that changed, or "show" when only the whole show tells.
  std::string change_message() const;
  /// The "curves" reply: every track's keys (or those of `channels`), flat.
  std::string curves_message(const std::optional<std::vector<std::string>>& channels) const;
  /// The "check" reply: what the show asks beyond the rig's limits.
  std::string check_message() const;
  /// The "waveform" reply: each audio track's sound, as peaks.
  std::string waveform_message() const;
  /// Hands the document's show to the session.
  void play_document();

  mutable std::mutex mutex_;  // document_, playing_, version_
  const rig::Rig& rig_;
  edit::ShowDocument document_;
  std::string show_path_;
  session::ShowSession* session_ = nullptr;
  std::vector<std::string> channel_names_;
  std::vector<std::string> target_names_;  ///< the show's targets, by effector, in its order
  /// The show the session was made with: it borrows it, so it lives as long as the studio.
  std::shared_ptr<const playback::Show> initial_;
  /// The show handed to the session last (its binding shares it).
  std::shared_ptr<const playback::Show> playing_;
  std::uint64_t version_ = 0;  ///< counts the show's changes, in every "show" message

  /// What a status message says, copied from the newest record.
  struct Snapshot {
    std::uint64_t tick = 0;
    double show_time_s = 0;
    bool paused = false, looping = false, estop = false, stop_requested = false;
    control::Phase phase = control::Phase::disabled;
    control::Fault fault;
    std::vector<session::ChannelRecord> channels;
    std::vector<firmware_iface::LinkCounters> links;
    std::vector<session::TargetRecord> targets;
  };
  std::string status_json(const Snapshot& s) const;

  std::mutex status_mutex_;  // the fields below
  bool fresh_ = false;
  Snapshot newest_;
  std::vector<session::CommandRecord> refused_;  ///< since the last take_status(), at most 64
};

}  // namespace avar::studio
