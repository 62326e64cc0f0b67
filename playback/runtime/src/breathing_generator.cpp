#include "avar/playback/runtime/breathing_generator.hpp"

#include <cmath>
#include <numbers>

namespace avar::playback {

BreathingGenerator::BreathingGenerator(const BreathingSpec& spec, std::uint64_t seed) : spec_(spec), random_(seed) {}

double BreathingGenerator::shape(double t) noexcept {
  const auto draw = [this] { return spec_.period_s * (1 + random_.uniform(-spec_.jitter, spec_.jitter)); };
  if (!started_) {
    started_ = true;
    cycle_start_ = t;
    cycle_s_ = draw();
  }
  while (t >= cycle_start_ + cycle_s_) {
    cycle_start_ += cycle_s_;
    cycle_s_ = draw();
  }
  return -std::cos(2 * std::numbers::pi * (t - cycle_start_) / cycle_s_);
}

void BreathingGenerator::add(double t, std::span<double> frame) noexcept {
  const double s = shape(t);
  for (const BreathingChannel& c : spec_.channels) frame[c.channel] += 0.5 * c.amplitude * s;
}

}  // namespace avar::playback
