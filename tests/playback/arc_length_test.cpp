// Arc length by adaptive quadrature, its inverse and the real-time table: known lengths, round
// trips within the bound over seeded random curves, monotone lookups.
#include "avar/playback/runtime/arc_length.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "parametric_curves.hpp"

namespace avar::playback {
namespace {

using testing::Bezier3;
using testing::Helix;

/// y = x^2 as a 1-D-in-the-plane curve (u, u^2, 0).
struct Parabola : ParametricCurve {
  double a = 2;
  double u_begin() const noexcept override { return 0; }
  double u_end() const noexcept override { return a; }
  Eigen::Vector3d position(double u) const noexcept override { return {u, u * u, 0}; }
  Eigen::Vector3d derivative(double u) const noexcept override { return {1, 2 * u, 0}; }
  double length() const { return 0.5 * a * std::sqrt(1 + 4 * a * a) + 0.25 * std::asinh(2 * a); }
};

struct Line1D : ParametricCurve {
  double u_begin() const noexcept override { return -1; }
  double u_end() const noexcept override { return 3; }
  Eigen::Vector3d position(double u) const noexcept override { return {2.5 * u, 0, 0}; }
  Eigen::Vector3d derivative(double) const noexcept override { return {2.5, 0, 0}; }
};

/// A speed with a kink: p(u) = (u |u| / 2, 0, 0), so |p'(u)| = |u|, over [-1, 1.3].
struct KinkedSpeed : ParametricCurve {
  double u_begin() const noexcept override { return -1; }
  double u_end() const noexcept override { return 1.3; }
  Eigen::Vector3d position(double u) const noexcept override { return {0.5 * u * std::abs(u), 0, 0}; }
  Eigen::Vector3d derivative(double u) const noexcept override { return {std::abs(u), 0, 0}; }
  static double length_to(double u) { return u <= 0 ? 0.5 * (1 - u * u) : 0.5 + 0.5 * u * u; }
};

constexpr double kTol = 1e-9;

TEST(ArcLength, KnownLengths) {
  EXPECT_NEAR(arc_length(Line1D{}, -1, 3, kTol), 10.0, kTol);
  const Helix arc(2.0, 0.0, 0.0, 2.0);  // circle arc of radius 2 over 2 rad
  EXPECT_NEAR(arc_length(arc, 0, 2, kTol), 4.0, kTol);
  const Helix helix(1.5, 0.4, 0.0, 4 * M_PI);
  EXPECT_NEAR(arc_length(helix, 0, 4 * M_PI, kTol), helix.length(), kTol);
  const Parabola parabola;
  EXPECT_NEAR(arc_length(parabola, 0, 2, kTol), parabola.length(), kTol);
  EXPECT_NEAR(arc_length(parabola, 2, 0, kTol), -parabola.length(), kTol);
  EXPECT_EQ(arc_length(parabola, 1, 1, kTol), 0.0);
}

/// A curve whose derivative overflows (a path point at 1e308 did this): infinite length.
struct Overflowing : ParametricCurve {
  double u_begin() const noexcept override { return 0; }
  double u_end() const noexcept override { return 1; }
  Eigen::Vector3d position(double u) const noexcept override { return {1e308 * u, 0, 0}; }
  Eigen::Vector3d derivative(double) const noexcept override { return {1e308, -1e308, 1e308}; }
};

TEST(ArcLength, NonFiniteLengthReturnsAtOnceInsteadOfSubdividingForever) {
  // Before: inf - inf never met the tolerance, and the quadrature split to depth 40 everywhere.
  EXPECT_FALSE(std::isfinite(arc_length(Overflowing{}, 0, 1, kTol)));
}

TEST(ArcLength, LooserToleranceStillWithinItsBound) {
  const Parabola parabola;
  for (double tol : {1e-2, 1e-4, 1e-6}) EXPECT_NEAR(arc_length(parabola, 0, 2, tol), parabola.length(), tol) << tol;
}

TEST(ArcLength, InverseOfKnownCurves) {
  const Helix helix(1.5, 0.4, 0.0, 4 * M_PI);
  const double speed = std::sqrt(1.5 * 1.5 + 0.4 * 0.4);
  for (double s : {0.0, 0.3, 5.0, 10.0, helix.length()})
    EXPECT_NEAR(parameter_at_length(helix, s, kTol), s / speed, kTol / speed) << s;
  EXPECT_EQ(parameter_at_length(helix, -1, kTol), 0.0);
  EXPECT_EQ(parameter_at_length(helix, 1e9, kTol), 4 * M_PI);
}

TEST(ArcLength, InverseRoundTripsOnRandomCurves) {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const Bezier3 curve = Bezier3::random(rng);
    const double total = arc_length(curve, 0, 1, 1e-10);
    std::uniform_real_distribution<double> fraction(0, 1);
    for (int i = 0; i < 10; ++i) {
      const double s = fraction(rng) * total;
      const double u = parameter_at_length(curve, s, 1e-8);
      ASSERT_NEAR(arc_length(curve, 0, u, 1e-11), s, 1e-8 + 1e-11) << "seed " << seed;
    }
  }
}

TEST(ArcLengthTable, MatchesQuadratureWithinTheBoundAndIsMonotone) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    const Bezier3 curve = Bezier3::random(rng);
    const double tol = 1e-6;
    const ArcLengthTable table(curve, tol);
    ASSERT_NEAR(table.total_length(), arc_length(curve, 0, 1, 1e-11), tol) << "seed " << seed;
    double previous_u = 0;
    for (int i = 0; i <= 500; ++i) {
      const double s = table.total_length() * i / 500.0;
      const double u = table.parameter_at(s);
      ASSERT_GE(u, previous_u) << "seed " << seed << " s " << s;
      previous_u = u;
      ASSERT_NEAR(arc_length(curve, 0, u, 1e-11), s, tol) << "seed " << seed << " s " << s;
      ASSERT_NEAR(table.length_at(u), s, 1e-9 * table.total_length()) << "seed " << seed;
    }
  }
}

TEST(ArcLengthTable, HalvesOnlyTheIntervalsAroundAKinkOfTheSpeed) {
  // The Hermite piece cannot follow the kink at u = 0: the interval holding it is halved down to
  // the narrowest allowed, and the rest of the table stays coarse.
  const KinkedSpeed curve;
  const double tol = 1e-9;
  const ArcLengthTable table(curve, tol);
  EXPECT_LE(table.intervals(), 200u);
  EXPECT_NEAR(table.total_length(), KinkedSpeed::length_to(1.3), tol);
  for (int i = 0; i <= 1000; ++i) {
    const double u = -1 + 2.3 * i / 1000.0;
    ASSERT_NEAR(table.length_at(u), KinkedSpeed::length_to(u), tol) << "u " << u;
    const double s = table.total_length() * i / 1000.0;
    ASSERT_NEAR(KinkedSpeed::length_to(table.parameter_at(s)), s, tol) << "s " << s;
  }
}

TEST(ArcLengthTable, RejectsBadArguments) {
  const Helix helix(1, 0, 0, 1);
  EXPECT_THROW(ArcLengthTable(helix, 0), std::invalid_argument);
  const Helix empty(1, 0, 1, 1);
  EXPECT_THROW(ArcLengthTable(empty, 1e-6), std::invalid_argument);
}

}  // namespace
}  // namespace avar::playback
