#include "avar/playback/runtime/idle_generator.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace avar::playback {
namespace {

constexpr double kIdleNoiseSpeedShare = 0.9;

void idle_check_channel(std::size_t channel, std::size_t frame, const char* what) {
  if (channel >= frame)
    throw std::invalid_argument(std::string("idle ") + what + " names channel " + std::to_string(channel) + " of " +
                                std::to_string(frame));
}

}  // namespace

IdleGenerator::IdleGenerator(const IdleSpec& spec, std::uint64_t seed)
    : spec_(spec), drives_(spec.limits.size(), 0), set_by_gaze_or_blink_(spec.limits.size(), 0) {
  const std::size_t n = spec_.limits.size();
  const auto mark = [&](std::size_t c, const char* what, bool sets) {
    idle_check_channel(c, n, what);
    drives_[c] = 1;
    if (sets) set_by_gaze_or_blink_[c] = 1;
  };
  noise_.reserve(spec_.noise.size());
  for (std::size_t i = 0; i < spec_.noise.size(); ++i) {
    NoiseSpec& s = spec_.noise[i];
    mark(s.channel, "noise", false);
    const IdleChannelLimits& l = spec_.limits[s.channel];
    s.octaves = std::clamp(s.octaves, 1, 8);
    s.amplitude = std::clamp(s.amplitude, 0.0, std::max(0.0, std::min(l.rest - l.low(), l.high() - l.rest)));
    const double speed = s.amplitude * s.frequency * GradientNoise::slope_bound(s.octaves);
    if (l.max_velocity > 0 && speed > kIdleNoiseSpeedShare * l.max_velocity)
      s.frequency *= kIdleNoiseSpeedShare * l.max_velocity / speed;
    noise_.emplace_back(behaviour_seed(seed, 100 + i));
  }
  if (spec_.blinks) {
    for (const BlinkLid& lid : spec_.blinks->lids) mark(lid.channel, "blinks", true);
    blinks_.emplace(*spec_.blinks, spec_.limits, behaviour_seed(seed, 1));
  }
  if (spec_.gaze) {
    const GazeSpec& g = *spec_.gaze;
    for (const auto& c : {g.eyes_pan, g.eyes_tilt, g.left_pan, g.right_pan, g.head_pan, g.head_tilt})
      if (c) mark(*c, "gaze", true);
    if (g.look_at)
      for (const std::size_t c : g.look_at->eye_channels) mark(c, "gaze", true);
    gaze_.emplace(g, spec_.limits, behaviour_seed(seed, 2));
  }
  if (spec_.breathing) {
    for (const BreathingChannel& c : spec_.breathing->channels) mark(c.channel, "breathing", false);
    breathing_.emplace(*spec_.breathing, behaviour_seed(seed, 3));
  }
}

void IdleGenerator::sample(double t, std::span<double> frame) noexcept {
  if (frame.size() != drives_.size()) return;
  for (std::size_t c = 0; c < frame.size(); ++c)
    if (drives_[c] && !set_by_gaze_or_blink_[c]) frame[c] = spec_.limits[c].rest;
  if (gaze_) gaze_->sample(t, frame);
  if (blinks_) blinks_->sample(t, frame);
  for (std::size_t i = 0; i < noise_.size(); ++i) {
    const NoiseSpec& s = spec_.noise[i];
    frame[s.channel] += s.amplitude * noise_[i].fractal(t * s.frequency, s.octaves);
  }
  if (breathing_) breathing_->add(t, frame);
  for (std::size_t c = 0; c < frame.size(); ++c)
    if (drives_[c]) frame[c] = std::clamp(frame[c], spec_.limits[c].low(), spec_.limits[c].high());
  // Look-at eyes last: they are aimed with the head where noise and breathing have put it.
  if (gaze_ && spec_.gaze->look_at) {
    gaze_->aim_eyes(frame);
    for (const std::size_t c : spec_.gaze->look_at->eye_channels)
      frame[c] = std::clamp(frame[c], spec_.limits[c].low(), spec_.limits[c].high());
  }
}

}  // namespace avar::playback
