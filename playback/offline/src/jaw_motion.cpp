// From the envelope to the jaw: gate, attack/release, curve, lead (see jaw_from_audio.hpp).
#include <algorithm>
#include <cmath>

#include "avar/playback/offline/jaw_from_audio.hpp"

namespace avar::playback {
namespace {

constexpr double kCloseUndershoot = 0.05;

}  // namespace

std::vector<double> gated_opening(std::span<const double> envelope_db, const JawOptions& o) {
  validate(o);
  const double close_db = o.gate_db - o.hysteresis_db;
  const double dt = 1 / o.frame_rate_hz;
  // One-pole smoothing: each frame moves 1 - exp(-dt / tau) of the way to the target.
  const auto pole = [dt](double tau) { return tau > 0 ? 1 - std::exp(-dt / tau) : 1.0; };
  const double attack = pole(o.attack_s);
  const double release = pole(o.release_s);
  std::vector<double> opening;
  opening.reserve(envelope_db.size());
  bool gate_open = false;
  double current = 0;
  for (const double level : envelope_db) {
    if (!gate_open && level >= o.gate_db) gate_open = true;
    if (gate_open && level < close_db) gate_open = false;
    const double target = gate_open ? std::clamp((level - close_db) / (o.full_db - close_db), 0.0, 1.0) : 0.0;
    // Closing aims a little below closed and stops there, so the jaw reaches exactly closed in
    // finite time (about 3 release constants from fully open) instead of creeping towards it.
    const double aim = target > 0 ? target : -kCloseUndershoot;
    current = std::max(0.0, current + (aim > current ? attack : release) * (aim - current));
    opening.push_back(current);
  }
  return opening;
}

JawMotion jaw_from_audio(std::span<const float> samples, double sample_rate_hz, const JawOptions& o) {
  JawMotion motion;
  motion.envelope_db = speech_envelope_db(samples, sample_rate_hz, o);
  const std::vector<double> opening = gated_opening(motion.envelope_db, o);
  const std::size_t n = opening.size();
  motion.times.reserve(n);
  motion.values.reserve(n);
  // The lead in frames: value at frame k is the opening at k + shift, linearly interpolated;
  // past the end the last opening holds.
  const double shift = o.lead_s * o.frame_rate_hz;
  for (std::size_t k = 0; k < n; ++k) {
    const double source = std::min(static_cast<double>(k) + shift, static_cast<double>(n - 1));
    const auto i = static_cast<std::size_t>(std::floor(source));
    const double f = source - static_cast<double>(i);
    const double a = opening[i];
    const double b = i + 1 < n ? opening[i + 1] : a;
    const double open = a + f * (b - a);
    motion.times.push_back(static_cast<double>(k) / o.frame_rate_hz);
    motion.values.push_back(open == 0 ? o.closed : o.closed + (o.open - o.closed) * std::pow(open, o.curve));
  }
  return motion;
}

double time_to_half_open(double distance, double max_velocity, double max_acceleration) {
  const double d = std::abs(distance);
  if (!(max_velocity > 0) || !(max_acceleration > 0)) return 0;
  const double full = d <= max_velocity * max_velocity / max_acceleration ? 2 * std::sqrt(d / max_acceleration)
                                                                          : d / max_velocity + max_velocity / max_acceleration;
  return full / 2;
}

}  // namespace avar::playback
