#include "avar/session/cue_player.hpp"

#include "avar/control/controller.hpp"

#include <algorithm>
#include <cmath>

namespace avar::session {
namespace {

/// Rounding in show time's sums (a tick's 0.02 s added fifty times is not quite 1 s).
constexpr double kTimeEpsilonS = 1e-9;

}  // namespace

CuePlayer::CuePlayer(const playback::Show& show, control::TickObserver* next) : show_(show), next_(next) {
  std::vector<firmware_iface::OscCueMessage> messages;
  for (const playback::Cue& cue : show.cues) {
    if (!cue.is_osc()) continue;
    firmware_iface::OscCueMessage m;
    m.host = cue.osc_host;
    m.port = cue.osc_port;
    m.address = cue.osc_address;
    for (const playback::CueArgument& a : cue.osc_arguments) m.arguments.push_back({a.type, a.number, a.text});
    messages.push_back(std::move(m));
    times_.push_back(cue.time);
  }
  if (!messages.empty()) sender_ = std::make_unique<firmware_iface::OscCueSender>(messages);
}

void CuePlayer::fire_until(double t) noexcept {
  while (next_cue_ < times_.size() && times_[next_cue_] <= t) {
    (void)sender_->fire(next_cue_++);
    ++fired_;
  }
}

void CuePlayer::after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& c) {
  if (next_) next_->after_tick(tick, now_s, dt_s, lateness_s, c);
  if (!sender_ || c.phase() != control::Phase::running) return;
  const double show_t = c.show_time();  // grows across passes; negative in the lead-in
  if (show_t < 0) return;
  const double duration = show_.duration;
  const auto pass = show_.loop && duration > 0 ? static_cast<std::int64_t>(std::floor(show_t / duration)) : 0;
  const double t = show_.local_time(show_t);
  const double step = started_ ? show_t - last_show_time_ : show_t;
  started_ = true;
  last_show_time_ = show_t;
  if (step < -kJumpS || step > dt_s + kJumpS || pass < pass_) {
    // A jump lands as a tick would: what it skipped does not fire, the cues within a tick
    // before where it landed do (a loop starting over lands just past 0), the later ones wait.
    pass_ = pass;
    next_cue_ =
        static_cast<std::size_t>(std::lower_bound(times_.begin(), times_.end(), t - dt_s - kTimeEpsilonS) - times_.begin());
  } else if (pass > pass_) {
    // A looping show wrapped: the rest of the last pass, then a new pass.
    fire_until(duration);
    next_cue_ = 0;
    pass_ = pass;
  }
  fire_until(t);
}

void CuePlayer::flush() {
  if (sender_) sender_->flush();
}

}  // namespace avar::session
