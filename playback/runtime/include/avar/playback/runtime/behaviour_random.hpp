#pragma once
// The idle behaviours' random numbers: SplitMix64 with our own mapping to doubles, so a seed gives
// the same figure on every standard library (std::uniform_real_distribution is not specified
// bit for bit). Real-time safe, no allocation; one generator per user (not thread-safe).

#include <cstdint>

namespace avar::playback {

class BehaviourRandom {
 public:
  explicit BehaviourRandom(std::uint64_t seed) noexcept : state_(seed) {}

  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 random bits.
  double unit() noexcept { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * unit(); }
  /// True with probability p.
  bool chance(double p) noexcept { return unit() < p; }

 private:
  std::uint64_t state_;
};

/// A seed of its own for stream `stream` of a run seeded with `seed` (each behaviour and each
/// channel draws from its own stream, so adding one does not change the others).
inline std::uint64_t behaviour_seed(std::uint64_t seed, std::uint64_t stream) noexcept {
  BehaviourRandom mix(seed ^ (stream * 0xD1B54A32D192ED03ULL));
  return mix.next();
}

}  // namespace avar::playback
