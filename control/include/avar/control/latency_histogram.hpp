#pragma once
// A fixed-size histogram of durations (1 µs buckets up to 20 ms, then one overflow bucket, and
// the exact maximum) for wake-up lateness and stage times. record() is real-time safe: no
// allocation, no lock; one writer thread at a time.

#include <array>
#include <cstdint>
#include <memory>

namespace avar::control {

class LatencyHistogram {
 public:
  static constexpr std::int64_t kBucketNs = 1000;
  static constexpr std::size_t kBuckets = 20000;

  LatencyHistogram();
  void record(std::int64_t ns) noexcept;
  std::uint64_t count() const noexcept { return count_; }
  std::int64_t max_ns() const noexcept { return max_ns_; }
  /// The duration below which `fraction` (0..1) of the samples lie, to bucket resolution
  /// (upper bucket edge; the exact maximum for the top). 0 when empty.
  std::int64_t percentile_ns(double fraction) const noexcept;

 private:
  std::unique_ptr<std::array<std::uint64_t, kBuckets + 1>> buckets_;  // heap: 160 KB
  std::uint64_t count_ = 0;
  std::int64_t max_ns_ = 0;
};

}  // namespace avar::control
