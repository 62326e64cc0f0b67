#pragma once
// Breathing over time (BreathingSpec): one slow cycle, each with a period drawn within the
// jitter, moving its channels by −amplitude/2 · cos 2πφ about rest (at rest speed at every cycle
// boundary, so a new period joins smoothly). Real-time safe sample(); times must not go back.

#include <cstdint>
#include <span>

#include "avar/playback/runtime/behaviour_random.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

class BreathingGenerator {
 public:
  BreathingGenerator(const BreathingSpec& spec, std::uint64_t seed);

  /// The cycle's shape at time t: −cos 2πφ, in [−1, 1].
  double shape(double t) noexcept;
  /// Adds each breathing channel's offset (channel units) at time t to frame.
  void add(double t, std::span<double> frame) noexcept;

 private:
  BreathingSpec spec_;
  BehaviourRandom random_;
  double cycle_start_ = 0, cycle_s_ = 0;
  bool started_ = false;
};

}  // namespace avar::playback
