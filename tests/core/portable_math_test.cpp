// The curve engine's portable elementary functions against glibc's: within a few units in the
// last place over seeded arguments in the domains the curves use, and the special values right.
// (That they give the same bits in WebAssembly is tests/tools/wasm_curves_test.mjs's to show.)
#include "avar/core/portable_math.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>

namespace avar::pmath {
namespace {

/// Units in the last place between two finite doubles of any signs.
std::uint64_t ulps_apart(double a, double b) {
  if (a == b) return 0;
  const auto ordered = [](double v) {
    const auto bits = std::bit_cast<std::int64_t>(v);
    return bits < 0 ? std::numeric_limits<std::int64_t>::min() - bits : bits;
  };
  const std::int64_t x = ordered(a), y = ordered(b);
  return x > y ? static_cast<std::uint64_t>(x - y) : static_cast<std::uint64_t>(y - x);
}

/// The worst distance between `mine` and `reference` over 200,000 seeded arguments in [lo, hi].
std::uint64_t worst_ulps(const std::function<double(double)>& mine, const std::function<double(double)>& reference, double lo,
                         double hi) {
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> arg(lo, hi);
  std::uint64_t worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = arg(random);
    worst = std::max(worst, ulps_apart(mine(x), reference(x)));
  }
  return worst;
}

TEST(PortableMath, SineAndCosineWithinTwoUlpsOfGlibc) {
  EXPECT_LE(worst_ulps([](double x) { return sin(x); }, [](double x) { return std::sin(x); }, -10, 10), 2u);
  EXPECT_LE(worst_ulps([](double x) { return cos(x); }, [](double x) { return std::cos(x); }, -10, 10), 2u);
  EXPECT_LE(worst_ulps([](double x) { return sin(x); }, [](double x) { return std::sin(x); }, -1e5, 1e5), 3u);
  EXPECT_EQ(sin(0.0), 0.0);
  EXPECT_EQ(cos(0.0), 1.0);
  EXPECT_TRUE(std::isnan(sin(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(cos(std::numeric_limits<double>::quiet_NaN())));
}

TEST(PortableMath, ArcSineAndArcCosineWithinTwoUlpsOfGlibc) {
  EXPECT_LE(worst_ulps([](double x) { return asin(x); }, [](double x) { return std::asin(x); }, -1, 1), 2u);
  EXPECT_LE(worst_ulps([](double x) { return acos(x); }, [](double x) { return std::acos(x); }, -1, 1), 2u);
  EXPECT_EQ(asin(1.0), kHalfPi);
  EXPECT_EQ(asin(-1.0), -kHalfPi);
  EXPECT_EQ(acos(1.0), 0.0);
  EXPECT_EQ(acos(-1.0), kPi);
  EXPECT_TRUE(std::isnan(asin(1.0000001)));
  EXPECT_TRUE(std::isnan(acos(-1.5)));
}

TEST(PortableMath, CubeRootWithinFourUlpsOfGlibc) {
  EXPECT_LE(worst_ulps([](double x) { return cbrt(x); }, [](double x) { return std::cbrt(x); }, -1e6, 1e6), 4u);
  EXPECT_LE(worst_ulps([](double x) { return cbrt(x); }, [](double x) { return std::cbrt(x); }, -1e-3, 1e-3), 4u);
  EXPECT_EQ(cbrt(27.0), 3.0);
  EXPECT_EQ(cbrt(-8.0), -2.0);
  EXPECT_EQ(cbrt(0.0), 0.0);
  EXPECT_TRUE(std::signbit(cbrt(-0.0)));
  EXPECT_EQ(cbrt(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
}

TEST(PortableMath, PowersOfTwoWithinAnUlpOfGlibc) {
  EXPECT_LE(worst_ulps([](double x) { return exp2(x); }, [](double x) { return std::pow(2.0, x); }, -30, 30), 1u);
  EXPECT_LE(worst_ulps([](double x) { return exp2(x); }, [](double x) { return std::pow(2.0, x); }, -1020, 1020), 1u);
  for (int k = -1074; k < 1024; ++k) EXPECT_EQ(exp2(k), std::ldexp(1.0, k)) << k;
  EXPECT_EQ(exp2(1024.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(exp2(-2000.0), 0.0);
}

TEST(PortableMath, HypotenuseWithinTwoUlpsOfGlibcAndNeverOverflowing) {
  EXPECT_LE(
      worst_ulps([](double x) { return hypot(x, 0.7 * x + 1); }, [](double x) { return std::hypot(x, 0.7 * x + 1); }, -100, 100),
      2u);
  EXPECT_EQ(hypot(3.0, 4.0), 5.0);
  EXPECT_EQ(hypot(0.0, -0.0), 0.0);
  EXPECT_NEAR(hypot(1e300, 1e300), std::sqrt(2.0) * 1e300, 1e285);
  EXPECT_EQ(hypot(-std::numeric_limits<double>::infinity(), 1.0), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace avar::pmath
