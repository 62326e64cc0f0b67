#pragma once
// Plays idle generators (IdleGenerator) as a pure function of time, so that a show's behaviour
// layer gives the same values at the same show time however it is reached: sampled at any rate,
// sought, or looped.
//
// The generators are stateful and advance with time; their state is advanced only on a fixed
// grid of kBehaviourStep seconds (the generators' own times 0, h, 2h, ...). The value at time τ is
// the state at the last grid point at or before τ, copied and sampled at τ: it depends on the
// seed and τ alone. Sequential playback costs one generator step per grid point passed, plus the
// copy. A time before the last grid point reached (a backward seek, a loop wrap) restores the
// generators' initial state and steps them forward again from 0: τ / kBehaviourStep steps (a
// 60 s span: 12 000 steps, about 0.7 ms on the development machine), the cost of that one
// sample only.
//
// Thread and real-time safety: construction allocates and may throw; sample() is real-time safe
// (restoring and copying assign into storage of the same sizes: no allocation).

#include <cstdint>
#include <span>
#include <vector>

#include "avar/playback/runtime/idle_generator.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

/// The grid on which a behaviour's generators advance, seconds (the gaze head filter's step).
inline constexpr double kBehaviourStep = 0.005;

class BehaviourPlayer {
 public:
  /// As IdleGenerator(spec, seed): spec.limits gives the frame size.
  BehaviourPlayer(const IdleSpec& spec, std::uint64_t seed);

  /// Writes every channel the behaviour drives at behaviour time `tau_s` (seconds since the
  /// behaviour began; below 0 is taken as 0) into frame (size spec.limits.size(); another size
  /// is left untouched). Real-time safe.
  void sample(double tau_s, std::span<double> frame) noexcept;

  /// Per channel: 1 where the behaviour drives it.
  std::span<const char> drives() const noexcept { return start_.drives(); }
  /// Grid steps taken and restarts from 0 so far (the cost of seeking, for tests).
  std::uint64_t steps() const noexcept { return steps_; }
  std::uint64_t restarts() const noexcept { return restarts_; }

 private:
  IdleGenerator start_;    ///< the generators as constructed: what a restart restores
  IdleGenerator stepped_;  ///< advanced to grid point step_
  IdleGenerator probe_;    ///< a copy of stepped_, sampled off the grid
  std::int64_t step_ = -1;
  std::vector<double> scratch_;
  std::uint64_t steps_ = 0, restarts_ = 0;
};

}  // namespace avar::playback
