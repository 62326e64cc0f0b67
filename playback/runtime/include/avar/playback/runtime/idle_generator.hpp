#pragma once
// Idle life (IdleSpec) as one frame per tick: gaze and blinks set their channels, noise and
// breathing add to them (or to rest), and every channel idle drives is kept inside its range
// less its soft margins. Deterministic: the same spec, seed and sample times give the same
// frames. Construction allocates (and clips the spec to the limits: noise amplitudes to the room
// about rest, noise frequencies to 90 % of the velocity limit); sample() is real-time safe, with
// times that do not go back.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "avar/playback/runtime/blink_generator.hpp"
#include "avar/playback/runtime/breathing_generator.hpp"
#include "avar/playback/runtime/gaze_generator.hpp"
#include "avar/playback/runtime/gradient_noise.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

class IdleGenerator {
 public:
  /// spec.limits gives the frame size; every channel index must be below it
  /// (std::invalid_argument otherwise).
  IdleGenerator(const IdleSpec& spec, std::uint64_t seed);

  /// Writes every channel idle drives at time t (s) into frame (size: spec.limits.size());
  /// the others are left as they are.
  void sample(double t, std::span<double> frame) noexcept;

  /// Per channel: 1 where idle drives it.
  std::span<const char> drives() const noexcept { return drives_; }
  const IdleSpec& spec() const noexcept { return spec_; }
  const std::optional<GazeGenerator>& gaze() const noexcept { return gaze_; }
  /// Look-at gaze: what aims the eyes (GazeGenerator::set_aim); borrowed, outlives this.
  void set_gaze_aim(GazeAim* aim) noexcept {
    if (gaze_) gaze_->set_aim(aim);
  }
  const std::optional<BlinkGenerator>& blinks() const noexcept { return blinks_; }

 private:
  IdleSpec spec_;
  std::vector<GradientNoise> noise_;  ///< one per spec_.noise entry
  std::optional<BlinkGenerator> blinks_;
  std::optional<GazeGenerator> gaze_;
  std::optional<BreathingGenerator> breathing_;
  std::vector<char> drives_;
  std::vector<char> set_by_gaze_or_blink_;
};

}  // namespace avar::playback
