#pragma once
// Per-channel tracking error between what the loop commanded and where the (simulated or
// reporting) actuator actually was. Sized once; add() is allocation-free.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace avar::session {

class TrackingStats {
 public:
  explicit TrackingStats(std::size_t channels);

  /// Adds one tick: error = commanded - measured for channels whose measurement is known.
  void add(std::span<const double> commanded, std::span<const double> measured, std::span<const bool> known) noexcept;

  bool has_samples(std::size_t channel) const noexcept { return count_[channel] > 0; }
  double max_abs_error(std::size_t channel) const noexcept { return max_abs_[channel]; }
  double rms_error(std::size_t channel) const noexcept;

 private:
  std::vector<double> max_abs_;
  std::vector<double> sum_sq_;
  std::vector<std::uint64_t> count_;
};

}  // namespace avar::session
