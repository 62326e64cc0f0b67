#include "jerk_residuals.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

namespace avar::control::jerk {
namespace {

TEST(JerkResiduals, CountsEachNewPeakOnceAndRemembersTheLastTwo) {
  const JerkLimits l{10, 100, 1000};
  const MotionState start{1, 2, 30};
  int evaluations = 0;
  Residuals residual(start, 4, Bounds(l), PlanSlack{}, evaluations);
  const Reach first = residual(3);
  EXPECT_EQ(first.distance, reach(2, 30, 3, Bounds(l)).distance - 3);
  residual(5);
  EXPECT_EQ(evaluations, 2);
  EXPECT_EQ(residual(3).distance, first.distance);
  EXPECT_EQ(residual(5).distance, residual(5).distance);
  EXPECT_EQ(evaluations, 2);
  EXPECT_TRUE(residual.remembers(3) && residual.remembers(5));
  EXPECT_EQ(residual.remembered(3).distance, first.distance);
  residual(7);
  EXPECT_EQ(evaluations, 3);
  EXPECT_FALSE(residual.remembers(3));
  EXPECT_TRUE(residual.remembers(5) && residual.remembers(7));
}

TEST(JerkResiduals, ToleranceIsTheRoundingOfThePositionsAndTheLastEvaluation) {
  const JerkLimits l{10, 100, 1000};
  const MotionState start{-3, 0, 0};
  int evaluations = 0;
  Residuals residual(start, 5, Bounds(l), PlanSlack{}, evaluations);
  EXPECT_EQ(residual.tolerance(), 4 * DBL_EPSILON * 8 + DBL_MIN);
  const Reach r = residual(2);
  EXPECT_EQ(residual.tolerance(), 4 * DBL_EPSILON * (8 + r.magnitude) + DBL_MIN);
}

TEST(JerkResiduals, AcceptsWithinRoundingOrWithinTheSlackOnlyForAPlanThatLastsBeyondItsHorizon) {
  const JerkLimits l{10, 100, 1000};
  int evaluations = 0;
  const PlanSlack slack{1e-3, 0.5};
  const Residuals residual(MotionState{}, 1, Bounds(l), slack, evaluations);
  Reach r{};
  r.duration = 1;
  Solution out;
  r.distance = 0.5 * residual.tolerance();
  ASSERT_TRUE(residual.accept(2, r, out));
  EXPECT_EQ(out.vp, 2);
  EXPECT_FALSE(out.loose);
  r.distance = -0.5e-3;
  ASSERT_TRUE(residual.accept(3, r, out));
  EXPECT_EQ(out.vp, 3);
  EXPECT_TRUE(out.loose);
  r.duration = 0.25;
  Solution short_plan;
  EXPECT_FALSE(residual.accept(3, r, short_plan));
  EXPECT_FALSE(short_plan.found());
}

}  // namespace
}  // namespace avar::control::jerk
