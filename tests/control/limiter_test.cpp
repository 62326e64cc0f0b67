#include "avar/control/limiter.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace avar::control {
namespace {

TEST(Limiter, ClampsTargetsIntoTheRangeAndCountsIt) {
  Limiter limiter({{0, 30, 100, 1000, 20000, 0}}, 0.01);
  limiter.reset(std::vector<double>{10});
  std::vector<double> out(1);
  for (int i = 0; i < 200; ++i) limiter.apply(std::vector<double>{45}, out);
  EXPECT_DOUBLE_EQ(out[0], 30);
  EXPECT_EQ(limiter.clamped(0), 200u);
  EXPECT_TRUE(limiter.settled());
}

TEST(Limiter, SoftMarginsKeepTargetsInside) {
  Limiter limiter({{0, 30, 100, 1000, 20000, 2}}, 0.01);
  std::vector<double> out(1);
  for (int i = 0; i < 200; ++i) limiter.apply(std::vector<double>{45}, out);
  EXPECT_DOUBLE_EQ(out[0], 28);
}

TEST(Limiter, RestToRestMoveTakesTravelPlusTheSmoothing) {
  // V = 2, A = 10, J = 100 at 1 kHz: N1 = V/A/dt = 200 ticks, N2 = 2A/J/dt = 200 ticks.
  Limiter limiter({{-10, 10, 2, 10, 100, 0}}, 0.001);
  std::vector<double> out(1);
  int ticks = 0;
  while (!limiter.settled() || out[0] != 5) {
    limiter.apply(std::vector<double>{5}, out);
    ++ticks;
    ASSERT_LT(ticks, 10000);
  }
  // 5 units at 2 units/s = 2.5 s of travel, plus V/A = 0.2 s and 2A/J = 0.2 s of smoothing
  // (the time-optimal profile needs 2.5 + 0.2 + 0.1 s).
  EXPECT_NEAR(ticks * 0.001, 2.5 + 0.2 + 0.2, 0.003);
  EXPECT_NEAR(limiter.delay(), 0.2, 0.002);
}

TEST(Limiter, ChannelsShareOneDelay) {
  // Very different limits, one common delay: a small step (within both velocity limits) comes
  // out half-way at the same tick on both channels, so channels that move together in the show
  // stay together on the figure.
  Limiter limiter({{0, 10, 5, 20, 100, 0}, {0, 10, 50, 2000, 1e5, 0}}, 0.01);
  std::vector<double> out(2);
  int half_way[2] = {-1, -1};
  for (int k = 0; k < 300; ++k) {
    limiter.apply(std::vector<double>{0.04, 0.04}, out);
    for (int c = 0; c < 2; ++c)
      if (half_way[c] < 0 && out[c] >= 0.02) half_way[c] = k;
  }
  EXPECT_GE(half_way[0], 0);
  EXPECT_NEAR(half_way[0], half_way[1], 1);
  EXPECT_NEAR(half_way[0] * 0.01, limiter.delay(), 0.011);
}

TEST(Limiter, NonFiniteTargetKeepsThePreviousGoalAndReportsIt) {
  Limiter limiter({{0, 10, 100, 1e4, 1e6, 0}, {0, 10, 100, 1e4, 1e6, 0}}, 0.02);
  limiter.reset(std::vector<double>{4, 5});
  std::vector<double> out(2);
  EXPECT_EQ(limiter.apply(std::vector<double>{std::numeric_limits<double>::quiet_NaN(), 6}, out), Status::not_finite);
  EXPECT_DOUBLE_EQ(out[0], 4);
  EXPECT_EQ(limiter.apply(std::vector<double>{std::numeric_limits<double>::infinity(), 6}, out), Status::not_finite);
  EXPECT_DOUBLE_EQ(out[0], 4);
}

TEST(Limiter, RejectsLimitsThatCannotWork) {
  EXPECT_THROW(Limiter({{0, 10, 0, 1, 1, 0}}, 0.01), std::invalid_argument);
  EXPECT_THROW(Limiter({{0, 10, 1, 1, 1, 0}}, 0), std::invalid_argument);
}

// Over a seeded family of 100,000 random limit sets, tick periods and target sequences (targets
// often far outside the range, some not finite), no output sample leaves the range, and the
// samples' velocity, acceleration and jerk (first, second and third differences) never exceed
// the limits; a held target is reached exactly and the channel comes to rest.
TEST(Limiter, NoSampleEverExceedsAnyLimitAndHeldTargetsAreReached) {
  const unsigned seed = 20261124;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
  constexpr int kFamilies = 100000;
  for (int family = 0; family < kFamilies; ++family) {
    const double range = log_uniform(0.1, 500);
    const double min = -range * u(rng);
    ChannelLimits cl{min, min + range, range * log_uniform(0.5, 10), 0, 0, u(rng) < 0.5 ? 0.0 : range * 0.05 * u(rng)};
    cl.max_acceleration = cl.max_velocity * log_uniform(2, 50);
    cl.max_jerk = cl.max_acceleration * log_uniform(5, 100);
    const double dt = std::vector<double>{0.001, 0.002, 0.005, 0.01, 0.02, 0.05}[rng() % 6];
    Limiter limiter({cl}, dt);
    limiter.reset(std::vector<double>{min + range * u(rng)});
    std::vector<double> out(1);
    std::vector<double> x{limiter.last()[0], limiter.last()[0], limiter.last()[0], limiter.last()[0]};
    // Rounding in the differences grows as 1/dt^k; allow for it explicitly.
    const double scale = 16 * DBL_EPSILON * (std::abs(min) + range);
    const auto check = [&](int tick) {
      x = {x[1], x[2], x[3], out[0]};
      const double v = (x[3] - x[2]) / dt;
      const double a = (x[3] - 2 * x[2] + x[1]) / (dt * dt);
      const double j = (x[3] - 3 * x[2] + 3 * x[1] - x[0]) / (dt * dt * dt);
      ASSERT_GE(out[0], cl.min) << "family " << family << " tick " << tick;
      ASSERT_LE(out[0], cl.max) << "family " << family << " tick " << tick;
      ASSERT_LE(std::abs(v), cl.max_velocity * (1 + 1e-9) + scale / dt) << "family " << family << " tick " << tick;
      ASSERT_LE(std::abs(a), cl.max_acceleration * (1 + 1e-9) + 4 * scale / (dt * dt)) << "family " << family << " tick " << tick;
      ASSERT_LE(std::abs(j), cl.max_jerk * (1 + 1e-9) + 8 * scale / (dt * dt * dt)) << "family " << family << " tick " << tick;
    };
    double target = 0;
    const int segments = 1 + static_cast<int>(rng() % 6);
    int tick = 0;
    for (int k = 0; k < segments; ++k) {
      target = u(rng) < 0.05 ? std::numeric_limits<double>::quiet_NaN() : min - 0.5 * range + 2 * range * u(rng);
      const int hold = 1 + static_cast<int>(rng() % 40);
      for (int h = 0; h < hold; ++h, ++tick) {
        limiter.apply(std::vector<double>{target}, out);
        check(tick);
      }
    }
    if (std::isnan(target)) target = min;
    const double margin = std::min(cl.soft_margin, range / 2);
    const double goal = std::clamp(target, cl.min + margin, cl.max - margin);
    for (int h = 0; !(limiter.settled() && out[0] == goal); ++h, ++tick) {
      limiter.apply(std::vector<double>{target}, out);
      check(tick);
      ASSERT_LT(h, static_cast<int>((range / cl.max_velocity + 4 * limiter.delay() + 1) / dt) + 10) << "family " << family;
    }
  }
}

}  // namespace
}  // namespace avar::control
