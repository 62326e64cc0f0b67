#pragma once
// The show clock a session owns (control::ShowClock): show time that pauses, jumps (seek,
// scrub) and loops on command. Until the first command it gives exactly the controller's own
// show time (loop time since the show started, less the lead-in), so an uncommanded run is the
// same run, bit for bit. A jump of show time reaches the figure through the limiter: the
// commands glide to the new frame at the channels' speed and acceleration limits, never snap.
//
// With an external clock (a timecode chase, a control surface) show time is that clock's, and
// the show-time commands are refused.
//
// Threads: everything runs on the loop thread (commands are applied by the session between
// ticks); real-time safe, no allocation.

#include <cstdint>

#include "avar/control/controller.hpp"
#include "avar/control/show_clock.hpp"
#include "avar/session/command_queue.hpp"

namespace avar::session {

class SessionClock final : public control::ShowClock {
 public:
  /// `lead_in_s`: the controller's lead-in (ControllerOptions::lead_in_s). `external`: show
  /// time from elsewhere (borrowed; nullptr: the session's own). Start playing unless `paused`.
  /// `hold_at_end` (SessionConfig::hold_at_end): show time pauses where a pass would end the
  /// show, instead of running on, and play there starts the show over.
  SessionClock(double lead_in_s, control::ShowClock* external, bool paused, bool hold_at_end = false) noexcept;

  /// The controller this clock serves (for its show start and duration); set before its first
  /// tick.
  void attach(const control::Controller& controller) noexcept { controller_ = &controller; }

  control::ShowClockReading read(double now_s) noexcept override;

  /// Applies a show-time command (play, pause, seek, scrub, loop) at loop time now_s, the time
  /// of the tick about to run. Other kinds are not the clock's: bad_value.
  CommandOutcome apply(const Command& command, double now_s) noexcept;

  bool paused() const noexcept { return !playing_; }
  /// Whether the show starts over at its end: as a loop command said, or as the show says.
  bool looping() const noexcept { return loop_ == -1 ? controller_ && controller_->show_loops() : loop_ == 1; }
  /// Show time as of the last read.
  double show_time() const noexcept { return last_show_s_; }

 private:
  double current(double now_s) const noexcept;
  void anchor(double show_s, double now_s) noexcept;
  double duration() const noexcept;

  double lead_in_s_;
  control::ShowClock* external_;
  const control::Controller* controller_ = nullptr;
  bool playing_;
  bool hold_at_end_;
  bool anchored_ = false;  ///< show time comes from the anchor (a command moved it)
  double anchor_show_s_ = 0;
  double anchor_now_s_ = 0;
  bool anchor_pending_ = false;  ///< anchored before the show ran: anchor_now_s_ is the first read's
  int loop_ = -1;                ///< -1: as the show says; 0: off; 1: on
  double pass_end_s_ = 0;        ///< loop off on a looping show: show time at which it ends
  double last_show_s_ = 0;
};

}  // namespace avar::session
