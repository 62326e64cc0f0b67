#pragma once
// Seeded one-dimensional gradient noise (Perlin's: a random slope at every integer, blended with
// the quintic fade 6f⁵ - 15f⁴ + 10f³, so the noise is C2), and its fractal sum over octaves.
// Construction fills the tables; evaluation is pure, real-time safe and allocation-free.

#include <array>
#include <cstdint>

namespace avar::playback {

class GradientNoise {
 public:
  explicit GradientNoise(std::uint64_t seed) noexcept;

  /// Noise at x (lattice units), in [-1, 1], 0 at every integer; repeats every 256 units.
  double at(double x) const noexcept;
  /// Sum of `octaves` (>= 1) layers, each at twice the frequency and half the amplitude of the
  /// one before, scaled back into [-1, 1].
  double fractal(double x, int octaves) const noexcept;

  /// Bound of |d fractal / dx| for `octaves` layers: the noise's speed is at most this times
  /// amplitude times frequency.
  static double slope_bound(int octaves) noexcept;

 private:
  std::array<std::uint8_t, 256> perm_{};
  std::array<double, 256> slope_{};
};

}  // namespace avar::playback
