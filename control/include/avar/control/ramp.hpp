#pragma once
// Soft stop and fail-safe moves: every channel eases from one pose to another along a half-cosine
// (zero speed at both ends), all channels arriving together; switched channels (digital ones)
// are on their goal from the start. Planning may allocate (it runs
// at set-up or reuses the buffers sized by the constructor); sampling is real-time safe.

#include <span>
#include <vector>

namespace avar::control {

class Ramp {
 public:
  /// at_once[channel] != 0: the channel switches (a digital channel): it samples its goal from
  /// the move's start and takes no part in its duration. Empty: none.
  explicit Ramp(std::size_t channels, std::vector<char> at_once = {});

  /// Plans a move from `from` to `to`. The duration is the shortest for which no channel's
  /// peak speed exceeds its peak_velocity (units/s), and at least min_duration_s. The peak
  /// speed of a half-cosine over T for a distance d is pi*d/(2T). Real-time safe.
  void plan(std::span<const double> from, std::span<const double> to, std::span<const double> peak_velocity,
            double min_duration_s) noexcept;

  double duration() const noexcept { return duration_; }

  /// Pose at time t_s after the start (clamped to [0, duration]). Real-time safe.
  void sample(double t_s, std::span<double> out) const noexcept;

 private:
  std::vector<double> from_;
  std::vector<double> to_;
  std::vector<char> at_once_;
  double duration_ = 0;
};

}  // namespace avar::control
