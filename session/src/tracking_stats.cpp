#include "avar/session/tracking_stats.hpp"

#include <algorithm>
#include <cmath>

namespace avar::session {

TrackingStats::TrackingStats(std::size_t channels) : max_abs_(channels, 0.0), sum_sq_(channels, 0.0), count_(channels, 0) {}

void TrackingStats::add(std::span<const double> commanded, std::span<const double> measured,
                        std::span<const bool> known) noexcept {
  for (std::size_t i = 0; i < max_abs_.size(); ++i) {
    if (!known[i]) continue;
    const double e = commanded[i] - measured[i];
    max_abs_[i] = std::max(max_abs_[i], std::abs(e));
    sum_sq_[i] += e * e;
    ++count_[i];
  }
}

double TrackingStats::rms_error(std::size_t channel) const noexcept {
  return count_[channel] ? std::sqrt(sum_sq_[channel] / static_cast<double>(count_[channel])) : 0.0;
}

}  // namespace avar::session
