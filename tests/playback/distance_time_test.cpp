// Distance-time functions: ends, monotone, continuity of distance and speed, speed as the
// derivative, and constant-speed traversal of a 3-D curve measured by arc length.
#include "avar/playback/runtime/distance_time.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "avar/playback/runtime/arc_length.hpp"
#include "parametric_curves.hpp"

namespace avar::playback {
namespace {

std::vector<DistanceTime> every_shape() {
  return {DistanceTime(DistanceTimeShape::linear),
          DistanceTime(DistanceTimeShape::sine),
          DistanceTime(DistanceTimeShape::cubic),
          DistanceTime(DistanceTimeShape::sine_constant_middle, 0.2, 0.7),
          DistanceTime(DistanceTimeShape::sine_constant_middle, 0.0, 1.0),
          DistanceTime(DistanceTimeShape::sine_constant_middle, 0.5, 0.5),
          DistanceTime(DistanceTimeShape::parabolic, 0.3, 0.6),
          DistanceTime(DistanceTimeShape::parabolic, 0.0, 0.0),
          DistanceTime(DistanceTimeShape::parabolic, 1.0, 1.0)};
}

TEST(DistanceTime, EndsMonotoneAndContinuous) {
  int index = 0;
  for (const DistanceTime& f : every_shape()) {
    SCOPED_TRACE(index++);
    EXPECT_EQ(f.distance(0), 0.0);
    EXPECT_NEAR(f.distance(1), 1.0, 1e-15);
    EXPECT_EQ(f.distance(-1), 0.0);
    EXPECT_EQ(f.distance(2), 1.0);
    const int n = 20000;
    double previous = 0, previous_speed = f.speed(0);
    for (int i = 1; i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      const double s = f.distance(t);
      ASSERT_GE(s, previous) << t;
      ASSERT_LT(s - previous, 5.0 / n) << "jump at " << t;  // speed <= 4 for every shape here
      // Speed is continuous: no jump larger than the largest acceleration (pi^2/2 / k) allows.
      ASSERT_LT(std::abs(f.speed(t) - previous_speed), 1e-2) << "speed jump at " << t;
      // Speed is the derivative of distance (central difference).
      if (i < n) {
        ASSERT_NEAR((f.distance(t + 1e-7) - f.distance(t - 1e-7)) / 2e-7, f.speed(t), 1e-5) << t;
      }
      previous = s;
      previous_speed = f.speed(t);
    }
  }
}

TEST(DistanceTime, KnownValues) {
  EXPECT_NEAR(DistanceTime(DistanceTimeShape::sine).distance(0.5), 0.5, 1e-15);
  EXPECT_NEAR(DistanceTime(DistanceTimeShape::cubic).distance(0.25), 0.15625, 1e-15);
  // Parabolic ease: top speed 2 / (1 + k2 - k1), reached at k1, held until k2.
  const DistanceTime parabolic(DistanceTimeShape::parabolic, 0.25, 0.75);
  EXPECT_NEAR(parabolic.speed(0.5), 2 / 1.5, 1e-15);
  EXPECT_NEAR(parabolic.distance(0.25), 0.5 * (2 / 1.5) * 0.25, 1e-15);
  EXPECT_EQ(parabolic.speed(0), 0.0);
  EXPECT_EQ(parabolic.speed(1), 0.0);
  EXPECT_NEAR(DistanceTime(DistanceTimeShape::sine_constant_middle, 0.25, 0.75).speed(0.5),
              1 / (0.25 * 2 / M_PI * 2 + 0.5), 1e-15);
}

TEST(DistanceTime, RejectsBadBreakpoints) {
  EXPECT_THROW(DistanceTime(DistanceTimeShape::parabolic, 0.6, 0.4), std::invalid_argument);
  EXPECT_THROW(DistanceTime(DistanceTimeShape::parabolic, -0.1, 0.4), std::invalid_argument);
  EXPECT_THROW(DistanceTime(DistanceTimeShape::sine_constant_middle, 0.1, 1.5), std::invalid_argument);
}

TEST(DistanceTime, ConstantSpeedTraversalCoversEqualDistancesPerStep) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    const auto curve = testing::Bezier3::random(rng);
    const double tol = 1e-7;
    const ArcLengthTable table(curve, tol);
    const DistanceTime linear(DistanceTimeShape::linear);
    const int steps = 200;
    const double step_length = table.total_length() / steps;
    double previous_u = table.parameter_at(0);
    for (int i = 1; i <= steps; ++i) {
      const double u = table.parameter_at(linear.distance(static_cast<double>(i) / steps) * table.total_length());
      // Each step's own length, by quadrature: equal within twice the table's bound.
      ASSERT_NEAR(arc_length(curve, previous_u, u, 1e-11), step_length, 2 * tol) << "seed " << seed << " step " << i;
      previous_u = u;
    }
  }
}

TEST(DistanceTime, EasedTraversalFollowsTheDistanceFunction) {
  const testing::Helix helix(1.0, 0.2, 0.0, 6.0);
  const ArcLengthTable table(helix, 1e-8);
  const DistanceTime ease(DistanceTimeShape::sine_constant_middle, 0.2, 0.8);
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    const double u = table.parameter_at(ease.distance(t) * table.total_length());
    EXPECT_NEAR(arc_length(helix, 0, u, 1e-12), ease.distance(t) * helix.length(), 1e-8) << t;
  }
}

}  // namespace
}  // namespace avar::playback
