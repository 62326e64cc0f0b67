#pragma once
// Fires a show's OSC cues during play: after each tick (on the loop thread) the cues whose time
// the show passed go, by index, to an OscCueSender whose thread sends them. Each cue fires once
// per pass of the show. Digital cues are step tracks of their channels (config's show reader)
// and need nothing here. Forwards every tick to the next observer first.

#include <cstdint>
#include <memory>
#include <vector>

#include "avar/control/runner.hpp"
#include "avar/firmware_iface/osc_cue_sender.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::session {

class CuePlayer final : public control::TickObserver {
 public:
  /// Prepares the show's OSC cues (none: nothing is started).
  CuePlayer(const playback::Show& show, control::TickObserver& next);
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
  control::TickObserver& next_;
  std::vector<double> times_;  ///< of the OSC cues, ascending; index = the sender's message
  std::unique_ptr<firmware_iface::OscCueSender> sender_;
  std::size_t next_cue_ = 0;
  double last_time_ = -1;
  std::uint64_t fired_ = 0;
};

}  // namespace avar::session
