#pragma once
// Fires a show's OSC cues during play: after each tick (on the loop thread) the cues whose time
// show time passed go, by index, to an OscCueSender whose thread sends them. Digital cues are
// step tracks of their channels (config's show reader) and need nothing here. Forwards every
// tick to the next observer first, when it has one.
//
// Show time is the controller's (Controller::show_time(): the session's clock, a timecode
// chase, a control surface), not loop time, so the rule holds under pause, seek, scrub and
// relocation alike: a cue fires when show time, playing forward, reaches it; once per pass of a
// looping show; never in the lead-in. A jump (show time moving back by more than kJumpS, or
// forward by more than a tick plus kJumpS, in one tick) lands as a tick would: the cues it
// skipped do not fire, those within one tick before where it landed do (a session's loop
// starting over lands just past 0), the later ones wait for show time to reach them. A session
// that starts past a cue skips it the same way.

#include <cstdint>
#include <memory>
#include <vector>

#include "avar/control/runner.hpp"
#include "avar/firmware_iface/osc_cue_sender.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::session {

class CuePlayer final : public control::TickObserver {
 public:
  /// Seconds of show time beyond one tick's worth that make a move of show time a jump: larger
  /// than a timecode frame's step or a chase's correction, smaller than any seek worth the name.
  static constexpr double kJumpS = 0.25;

  /// Prepares the show's OSC cues (none: nothing is started).
  explicit CuePlayer(const playback::Show& show) : CuePlayer(show, nullptr) {}
  /// Also forwards every tick to `next` (borrowed; nullptr: none).
  CuePlayer(const playback::Show& show, control::TickObserver* next);
  /// Real-time safe: no allocation, no lock.
  void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& c) override;
  /// Waits until every fired cue was sent. Not real-time.
  void flush();

  std::size_t osc_cues() const { return times_.size(); }
  std::uint64_t fired() const { return fired_; }
  std::uint64_t sent() const { return sender_ ? sender_->sent() : 0; }
  std::uint64_t failed() const { return sender_ ? sender_->failed() + sender_->dropped() : 0; }

 private:
  void fire_until(double t) noexcept;

  const playback::Show& show_;
  control::TickObserver* next_;
  std::vector<double> times_;  ///< of the OSC cues, ascending; index = the sender's message
  std::unique_ptr<firmware_iface::OscCueSender> sender_;
  std::size_t next_cue_ = 0;
  std::int64_t pass_ = 0;  ///< of a looping show: the pass the cues are armed for
  double last_show_time_ = 0;
  bool started_ = false;  ///< a running tick was seen
  std::uint64_t fired_ = 0;
};

}  // namespace avar::session
