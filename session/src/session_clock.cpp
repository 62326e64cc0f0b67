#include "avar/session/session_clock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace avar::session {

SessionClock::SessionClock(double lead_in_s, control::ShowClock* external, bool paused, bool hold_at_end) noexcept
    : lead_in_s_(lead_in_s), external_(external), playing_(!paused), hold_at_end_(hold_at_end) {
  if (paused) {
    anchored_ = true;
    anchor_pending_ = true;
    anchor_show_s_ = -lead_in_s;
  }
}

double SessionClock::duration() const noexcept { return controller_ ? controller_->show_duration() : 0.0; }

double SessionClock::current(double now_s) const noexcept {
  if (!anchored_) return now_s - controller_->show_start_time() - lead_in_s_;
  if (anchor_pending_ || !playing_) return anchor_show_s_;
  return anchor_show_s_ + (now_s - anchor_now_s_);
}

void SessionClock::anchor(double show_s, double now_s) noexcept {
  anchored_ = true;
  anchor_show_s_ = show_s;
  anchor_now_s_ = now_s;
}

control::ShowClockReading SessionClock::read(double now_s) noexcept {
  if (external_) {
    const control::ShowClockReading r = external_->read(now_s);
    last_show_s_ = r.show_time_s;
    return r;
  }
  if (anchor_pending_) {
    anchor_pending_ = false;
    anchor_now_s_ = now_s;
  }
  double t = current(now_s);
  bool stop = false;
  const double d = duration();
  if (loop_ == 1 && d > 0 && !controller_->show_loops() && t >= d) {
    // Loop on over a show that does not loop by itself: start over.
    t = std::fmod(t, d);
    anchor(t, now_s);
  }
  if (loop_ == 0 && controller_->show_loops() && t >= pass_end_s_) {
    if (hold_at_end_) {
      // Hold the pass's last frame (just before it wraps), paused.
      t = std::nextafter(pass_end_s_, 0.0);
      anchor(t, now_s);
      playing_ = false;
    } else {
      stop = true;
    }
  }
  if (hold_at_end_ && d > 0 && !controller_->show_loops() && loop_ != 1 && t >= d && playing_) {
    t = d;
    anchor(t, now_s);
    playing_ = false;
  }
  last_show_s_ = t;
  return {t, stop};
}

CommandOutcome SessionClock::apply(const Command& command, double now_s) noexcept {
  if (external_) return CommandOutcome::external_clock;
  const bool ran = controller_ && controller_->show_start_time() >= 0;
  // Before the show runs, the commands set where and how it starts.
  const double here = ran ? current(now_s) : (anchored_ ? anchor_show_s_ : -lead_in_s_);
  const auto jump_to = [&](double t) {
    const double d = duration();
    const double end = controller_ && !controller_->show_loops() ? d : std::numeric_limits<double>::infinity();
    anchor(std::clamp(t, 0.0, end), now_s);
    anchor_pending_ = !ran;
  };
  switch (command.kind) {
    case CommandKind::play:
      if (!playing_) {
        // At the end a held show starts over.
        const bool loops = controller_ && controller_->show_loops();
        const bool at_end =
            hold_at_end_ && controller_ && (loops ? loop_ == 0 && here >= std::nextafter(pass_end_s_, 0.0) : here >= duration());
        if (at_end && loops) pass_end_s_ = duration();
        jump_to(at_end ? 0.0 : here);
        playing_ = true;
      }
      return CommandOutcome::applied;
    case CommandKind::pause:
      if (playing_) {
        anchor(here, now_s);
        anchor_pending_ = !ran;
        playing_ = false;
      }
      return CommandOutcome::applied;
    case CommandKind::seek:
    case CommandKind::scrub:
      if (!std::isfinite(command.value)) return CommandOutcome::bad_value;
      jump_to(command.value);
      if (command.kind == CommandKind::scrub) playing_ = false;
      return CommandOutcome::applied;
    case CommandKind::loop:
      loop_ = command.value != 0 ? 1 : 0;
      if (loop_ == 0 && duration() > 0) pass_end_s_ = (std::floor(std::max(here, 0.0) / duration()) + 1) * duration();
      return CommandOutcome::applied;
    default: return CommandOutcome::bad_value;
  }
}

}  // namespace avar::session
