#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "jerk_bracket.hpp"
#include "jerk_refine.hpp"
#include "jerk_test_family.hpp"
#include "jerk_warm_start.hpp"

namespace avar::control::jerk {
namespace {

/// One plan's solve, stage by stage, from `hint`.
struct StagedSolve {
  int evaluations = 0;
  Residuals residual;
  Branches branches;
  Solution solution;
  WarmStart warm;
  StagedSolve(const MotionState& s, double goal, const JerkLimits& l, double hint)
      : residual(s, goal, Bounds(l), PlanSlack{}, evaluations),
        branches(s.v, s.a, l.velocity, Bounds(l)),
        warm(warm_start(hint, false, PlanSlack{}, l.velocity, branches, Bounds(l), residual, solution)) {}
};

TEST(JerkSolveStages, AWarmStartOnTheRootTakesOneEvaluation) {
  testing::JerkFamily family(20261214);
  for (int n = 0; n < 20000; ++n) {
    const auto [l, s, root] = family.draw();
    const double goal = s.p + reach(s.v, s.a, root, Bounds(l)).distance;
    StagedSolve solve(s, goal, l, root);
    ASSERT_TRUE(solve.solution.found()) << "n " << n;
    ASSERT_EQ(solve.solution.vp, root) << "n " << n;
    ASSERT_EQ(solve.evaluations, 1) << "n " << n;
  }
}

TEST(JerkSolveStages, TheBracketHoldsTheRootAndTheRefinementEndsOnIt) {
  testing::JerkFamily family(20261215);
  int bracketed = 0;
  for (int n = 0; n < 20000; ++n) {
    const JerkLimits l = family.limits();
    const Bounds k(l);
    const MotionState s = family.start(l);
    const double goal = family.goal(s);
    const double d = goal - s.p;
    // No hint: the bracket starts from the branch ends.
    StagedSolve solve(s, goal, l, std::numeric_limits<double>::quiet_NaN());
    ASSERT_FALSE(solve.solution.found());
    const Bracket br = bracket_root(solve.warm, l.velocity, l, solve.branches, k, solve.residual, solve.solution);
    if (!solve.solution.found()) {
      ++bracketed;
      ASSERT_LE(br.lo, br.hi) << "n " << n;
      ASSERT_LE(br.f_lo, 0) << "n " << n;
      ASSERT_GE(br.f_hi, 0) << "n " << n;
      ASSERT_EQ(br.f_lo, reach(s.v, s.a, br.lo, k).distance - d) << "n " << n;
      ASSERT_EQ(br.f_hi, reach(s.v, s.a, br.hi, k).distance - d) << "n " << n;
    }
    refine(br, solve.warm.resume, 1e-9 * (l.velocity / l.acceleration + l.acceleration / l.jerk), solve.branches, solve.residual,
           solve.solution);
    const Solution& out = solve.solution;
    ASSERT_TRUE(out.found()) << "n " << n;
    ASSERT_GE(out.cruise, 0) << "n " << n;
    // The plan's change, cruise and stop cover the distance (to the shift that plans absorb).
    const double miss = reach(s.v, s.a, out.vp, k).distance + out.cruise * out.vp - d;
    ASSERT_LE(std::abs(miss), kShiftable * solve.residual.tolerance()) << "n " << n;
    ASSERT_LE(solve.evaluations, 3 + kMaxRefinements) << "n " << n;
  }
  EXPECT_GT(bracketed, 3000);
}

}  // namespace
}  // namespace avar::control::jerk
