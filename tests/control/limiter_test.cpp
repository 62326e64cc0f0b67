#include "avar/control/limiter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace avar::control {
namespace {

TEST(Limiter, ClampsIntoRangeAndCountsIt) {
  Limiter limiter({{0, 30, 1000}});
  limiter.reset(std::vector<double>{10});
  std::vector<double> out(1);
  ASSERT_EQ(limiter.apply(std::vector<double>{45}, 0.02, out), Status::ok);
  EXPECT_DOUBLE_EQ(out[0], 30);
  EXPECT_EQ(limiter.clamped(0), 1u);
}

TEST(Limiter, VelocityLimitMovesAtMostVmaxTimesDt) {
  Limiter limiter({{-100, 100, 50}});
  limiter.reset(std::vector<double>{0});
  std::vector<double> out(1);
  limiter.apply(std::vector<double>{80}, 0.1, out);
  EXPECT_DOUBLE_EQ(out[0], 5);
  limiter.apply(std::vector<double>{80}, 0.1, out);
  EXPECT_DOUBLE_EQ(out[0], 10);
  EXPECT_EQ(limiter.rate_limited(0), 2u);
}

TEST(Limiter, NonFiniteTargetHoldsTheLastValueAndReportsIt) {
  Limiter limiter({{0, 10, 100}, {0, 10, 100}});
  limiter.reset(std::vector<double>{4, 5});
  std::vector<double> out(2);
  EXPECT_EQ(limiter.apply(std::vector<double>{std::numeric_limits<double>::quiet_NaN(), 6}, 0.02, out), Status::not_finite);
  EXPECT_DOUBLE_EQ(out[0], 4);
  EXPECT_DOUBLE_EQ(out[1], 6);
  EXPECT_EQ(limiter.apply(std::vector<double>{std::numeric_limits<double>::infinity(), 6}, 0.02, out), Status::not_finite);
  EXPECT_DOUBLE_EQ(out[0], 4);
}

// Over a seeded family of random limits and target sequences (including wild and non-finite
// targets), no output ever leaves its range or moves faster than its velocity limit.
TEST(Limiter, NoOutputEverExceedsRangeOrVelocity) {
  const unsigned seed = 20261124;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int family = 0; family < 200; ++family) {
    const std::size_t n = 1 + rng() % 8;
    std::vector<ChannelLimits> limits;
    for (std::size_t i = 0; i < n; ++i) {
      const double lo = -200 + 200 * u(rng);
      limits.push_back({lo, lo + 0.1 + 300 * u(rng), 0.5 + 2000 * u(rng)});
    }
    Limiter limiter(limits);
    std::vector<double> start(n), target(n), out(n), prev(n);
    for (std::size_t i = 0; i < n; ++i) start[i] = -500 + 1000 * u(rng);
    limiter.reset(start);
    for (std::size_t i = 0; i < n; ++i) prev[i] = limiter.last()[i];
    const double dt = 0.001 + 0.05 * u(rng);
    for (int k = 0; k < 500; ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        const double r = u(rng);
        target[i] = r < 0.02 ? std::numeric_limits<double>::quiet_NaN() : -1000 + 2000 * u(rng);
      }
      limiter.apply(target, dt, out);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_GE(out[i], limits[i].min);
        ASSERT_LE(out[i], limits[i].max);
        ASSERT_LE(std::abs(out[i] - prev[i]), limits[i].max_velocity * dt * (1 + 1e-12) + 1e-12);
        prev[i] = out[i];
      }
    }
  }
}

}  // namespace
}  // namespace avar::control
