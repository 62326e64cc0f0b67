#include "avar/control/latency_histogram.hpp"

#include <gtest/gtest.h>

namespace avar::control {
namespace {

TEST(LatencyHistogram, PercentilesToBucketResolution) {
  LatencyHistogram h;
  EXPECT_EQ(h.percentile_ns(0.5), 0);
  for (int i = 1; i <= 1000; ++i) h.record(i * 1000 - 500);  // 0.5 µs .. 999.5 µs
  EXPECT_EQ(h.count(), 1000u);
  EXPECT_EQ(h.percentile_ns(0.5), 500'000);
  EXPECT_EQ(h.percentile_ns(0.99), 990'000);
  EXPECT_EQ(h.percentile_ns(1.0), 999'500);  // the exact maximum caps the top bucket
  EXPECT_EQ(h.max_ns(), 999'500);
}

TEST(LatencyHistogram, OverflowKeepsTheExactMaximumAndNegativesCountAsZero) {
  LatencyHistogram h;
  h.record(-5);
  h.record(3'000'000'000);  // 3 s, far past the last bucket
  EXPECT_EQ(h.percentile_ns(0.5), 1000);
  EXPECT_EQ(h.percentile_ns(1.0), 3'000'000'000);
}

}  // namespace
}  // namespace avar::control
