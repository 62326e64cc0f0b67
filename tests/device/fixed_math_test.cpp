// The device engine's integer functions against the double ones they stand for, over seeded
// arguments: sin within 2^-27, 2^x within 2^-26 relative, the square root exact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "avar/device/fixed_math.hpp"

namespace avar::device {
namespace {

constexpr double kQ30d = 1073741824.0;

TEST(DeviceFixedMath, SinTurnsIsWithinTwoToTheMinus27) {
  std::mt19937 rng(11);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const auto phase = static_cast<std::uint32_t>(rng());
    const double expected = std::sin(2 * std::numbers::pi * phase / 4294967296.0);
    worst = std::max(worst, std::abs(sin_turns(phase) / kQ30d - expected));
  }
  EXPECT_LT(worst, std::ldexp(1.0, -27));
  EXPECT_EQ(sin_turns(0), 0);
  EXPECT_EQ(sin_turns(0x40000000u), kQ30);
  EXPECT_EQ(sin_turns(0xc0000000u), -kQ30);
  EXPECT_EQ(cos_turns(0), kQ30);
}

TEST(DeviceFixedMath, Exp2IsWithinTwoToTheMinus26Relative) {
  std::mt19937 rng(12);
  std::uniform_int_distribution<std::int64_t> x(-12 * kQ30, kQ30);
  for (int i = 0; i < 100000; ++i) {
    const std::int64_t a = x(rng);
    const double expected = std::exp2(static_cast<double>(a) / kQ30d);
    EXPECT_NEAR(static_cast<double>(exp2_q30(a)) / kQ30d, expected, expected * std::ldexp(1.0, -26) + std::ldexp(1.0, -30)) << a;
  }
  EXPECT_EQ(exp2_q30(0), kQ30);
  EXPECT_EQ(exp2_q30(-kQ30 * 10), kQ30 >> 10);
  EXPECT_EQ(exp2_q30(-kQ30 * 80), 0);
}

TEST(DeviceFixedMath, IntegerSquareRootIsExact) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t x = rng() >> (rng() % 64);
    const std::uint64_t r = isqrt64(x);
    EXPECT_LE(r * r, x);
    EXPECT_GT((r + 1) * (r + 1), x);
  }
  EXPECT_EQ(isqrt64(0), 0u);
  EXPECT_EQ(isqrt64(~std::uint64_t{0}), 0xffffffffu);
}

TEST(DeviceFixedMath, ShiftFloorRoundsTowardMinusInfinity) {
  EXPECT_EQ(shift_floor(5, 1), 2);
  EXPECT_EQ(shift_floor(-5, 1), -3);
  EXPECT_EQ(shift_floor(-4, 1), -2);
  EXPECT_EQ(shift_floor(-1, 30), -1);
  EXPECT_EQ(shift_floor(INT64_MIN, 63), -1);
}

}  // namespace
}  // namespace avar::device
