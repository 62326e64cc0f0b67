#include "avar/playback/runtime/gradient_noise.hpp"

#include <cmath>
#include <utility>

#include "avar/playback/runtime/behaviour_random.hpp"

namespace avar::playback {
namespace {

double gradient_noise_fade(double f) noexcept { return f * f * f * (f * (f * 6 - 15) + 10); }

}  // namespace

GradientNoise::GradientNoise(std::uint64_t seed) noexcept {
  BehaviourRandom random(seed);
  for (std::size_t i = 0; i < perm_.size(); ++i) perm_[i] = static_cast<std::uint8_t>(i);
  // Fisher-Yates with our own draws (std::shuffle's use of the engine is not specified).
  for (std::size_t i = perm_.size() - 1; i > 0; --i) std::swap(perm_[i], perm_[random.next() % (i + 1)]);
  for (double& s : slope_) s = random.uniform(-1.0, 1.0);
}

double GradientNoise::at(double x) const noexcept {
  const double cell = std::floor(x);
  const double f = x - cell;
  const auto i = static_cast<std::uint8_t>(static_cast<long long>(cell) & 255);
  const double g0 = slope_[perm_[i]];
  const double g1 = slope_[perm_[static_cast<std::uint8_t>(i + 1)]];
  const double a = g0 * f;
  const double b = g1 * (f - 1);
  // A single cell reaches at most 0.5 in magnitude: doubled, the noise spans [-1, 1].
  return 2 * (a + gradient_noise_fade(f) * (b - a));
}

double GradientNoise::fractal(double x, int octaves) const noexcept {
  double sum = 0, norm = 0, amplitude = 1, frequency = 1;
  for (int k = 0; k < octaves; ++k) {
    // Each octave is shifted so the lattice zeros of the octaves do not line up.
    sum += amplitude * at(x * frequency + 17.31 * k);
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2;
  }
  return norm > 0 ? sum / norm : 0;
}

double GradientNoise::slope_bound(int octaves) noexcept {
  // One octave: d/dx (a + fade·(b - a)) = (1 - fade)·g0 + fade·g1 + fade'·(b - a), whose size is
  // at most 1 + 15/8 (|g| <= 1, |b - a| <= 1, fade' <= 15/8); doubled, below 6.
  // Octave k has amplitude 2^-k and frequency 2^k: each adds the same slope; the sum is scaled
  // by 1 / Σ 2^-k.
  double norm = 0, amplitude = 1;
  for (int k = 0; k < octaves; ++k) {
    norm += amplitude;
    amplitude *= 0.5;
  }
  return norm > 0 ? 6.0 * octaves / norm : 0;
}

}  // namespace avar::playback
