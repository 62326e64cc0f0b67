#pragma once
// Per-channel motion limits applied to every command before it reaches a link: position range,
// then speed. Sized once; apply() is real-time safe (no allocation, no exception, no lock).

#include <cstdint>
#include <span>
#include <vector>

#include "avar/core/status.hpp"

namespace avar::control {

struct ChannelLimits {
  double min = 0;           ///< channel units
  double max = 1;           ///< channel units, > min
  double max_velocity = 1;  ///< channel units per second, > 0
};

class Limiter {
 public:
  explicit Limiter(std::vector<ChannelLimits> limits);

  /// Sets the last output (the pose the figure is known or assumed to be in). Values are
  /// clamped into range. Size must equal the channel count.
  void reset(std::span<const double> pose) noexcept;

  /// out[i] = target[i] clamped into [min, max], then moved at most max_velocity * dt_s from
  /// the previous output. A non-finite target holds that channel's previous output and the
  /// call returns Status::not_finite; otherwise Status::ok. target and out may alias.
  Status apply(std::span<const double> target, double dt_s, std::span<double> out) noexcept;

  std::size_t size() const noexcept { return limits_.size(); }
  const ChannelLimits& limits(std::size_t channel) const noexcept { return limits_[channel]; }
  std::span<const double> last() const noexcept { return last_; }
  /// Samples whose target lay outside [min, max] (channel index).
  std::uint64_t clamped(std::size_t channel) const noexcept { return clamped_[channel]; }
  /// Samples slowed down by the velocity limit.
  std::uint64_t rate_limited(std::size_t channel) const noexcept { return rate_limited_[channel]; }

 private:
  std::vector<ChannelLimits> limits_;
  std::vector<double> last_;
  std::vector<std::uint64_t> clamped_;
  std::vector<std::uint64_t> rate_limited_;
};

}  // namespace avar::control
