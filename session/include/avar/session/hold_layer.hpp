#pragma once
// Channels held at a value over the show: the top live layer of a session (control::LiveLayer),
// so what it sets still passes the controller's limiter and supervisor. A hold is clamped to
// the channel's range here; the limiter then moves the channel there within its speed and
// acceleration limits, and a release glides it back to the show the same way.
//
// Threads: hold() and release() are called by the session between ticks, apply() by the
// controller in the tick, all on the loop thread. Real-time safe: sized once, no allocation.

#include <cstddef>
#include <span>
#include <vector>

#include "avar/control/live_layer.hpp"
#include "avar/rig/rig.hpp"

namespace avar::session {

class HoldLayer final : public control::LiveLayer {
 public:
  /// `below`: layers under the holds (idle life, live inputs; borrowed, may be null).
  HoldLayer(const rig::Rig& rig, control::LiveLayer* below);

  /// Holds `channel` at `value` (channel units), clamped into the channel's [min, max]; returns
  /// the value held. Precondition: channel < channel count, value finite.
  double hold(std::size_t channel, double value) noexcept;
  void release(std::size_t channel) noexcept;
  bool held(std::size_t channel) const noexcept { return held_[channel] != 0; }
  std::size_t channel_count() const noexcept { return held_.size(); }

  void apply(double now_s, std::span<double> frame) noexcept override;
  /// The layers below move the goals; holds are of channels only.
  void apply_targets(double now_s, std::span<double> points) noexcept override {
    if (below_) below_->apply_targets(now_s, points);
  }

 private:
  control::LiveLayer* below_;
  std::vector<double> min_, max_, value_;
  std::vector<char> held_;
};

}  // namespace avar::session
