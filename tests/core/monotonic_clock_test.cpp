#include "avar/core/monotonic_clock.hpp"

#include <gtest/gtest.h>

#include <time.h>

#include <cstdint>

namespace avar {
namespace {

TEST(MonotonicClock, ReadsClockMonotonicInNanoseconds) {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  const std::int64_t before = static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
  const std::int64_t now = monotonic_ns();
  clock_gettime(CLOCK_MONOTONIC, &t);
  const std::int64_t after = static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
  EXPECT_LE(before, now);
  EXPECT_LE(now, after);
}

TEST(MonotonicClock, NeverGoesBack) {
  std::int64_t last = monotonic_ns();
  for (int i = 0; i < 1000; ++i) {
    const std::int64_t now = monotonic_ns();
    EXPECT_GE(now, last);
    last = now;
  }
}

}  // namespace
}  // namespace avar
