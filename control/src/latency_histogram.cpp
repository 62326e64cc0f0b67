#include "avar/control/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace avar::control {

LatencyHistogram::LatencyHistogram() : buckets_(std::make_unique<std::array<std::uint64_t, kBuckets + 1>>()) {}

void LatencyHistogram::record(std::int64_t ns) noexcept {
  ns = std::max<std::int64_t>(ns, 0);
  const auto bucket = static_cast<std::size_t>(std::min<std::int64_t>(ns / kBucketNs, kBuckets));
  ++(*buckets_)[bucket];
  ++count_;
  max_ns_ = std::max(max_ns_, ns);
}

std::int64_t LatencyHistogram::percentile_ns(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(count_)));
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b <= kBuckets; ++b) {
    seen += (*buckets_)[b];
    if (seen >= std::max<std::uint64_t>(rank, 1)) return b == kBuckets ? max_ns_ : std::min(max_ns_, static_cast<std::int64_t>(b + 1) * kBucketNs);
  }
  return max_ns_;
}

}  // namespace avar::control
