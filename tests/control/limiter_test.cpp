#include "avar/control/limiter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace avar::control {
namespace {

TEST(Limiter, ClampsTargetsIntoTheRangeAndCountsIt) {
  Limiter limiter({{0, 30, 100, 1000, 20000, 0}}, 0.01);
  limiter.reset(std::vector<double>{10});
  std::vector<double> out(1);
  for (int i = 0; i < 200; ++i) EXPECT_EQ(limiter.apply(std::vector<double>{45}, out), Status::ok);
  EXPECT_DOUBLE_EQ(out[0], 30);
  EXPECT_EQ(limiter.clamped(0), 200u);
  EXPECT_TRUE(limiter.settled());
}

TEST(Limiter, SoftMarginsKeepTargetsInside) {
  Limiter limiter({{0, 30, 100, 1000, 20000, 2}}, 0.01);
  std::vector<double> out(1);
  for (int i = 0; i < 200; ++i) EXPECT_EQ(limiter.apply(std::vector<double>{45}, out), Status::ok);
  EXPECT_DOUBLE_EQ(out[0], 28);
}

/// Checks every command against the range and, by its 1st/2nd/3rd differences over dt, the
/// velocity, acceleration and jerk limits (with a rounding allowance that grows as 1/dt^k), and
/// that braking at the limits from the channel's state stops within the range.
class LimitChecker {
 public:
  LimitChecker(const ChannelLimits& cl, double dt, double start)
      : cl_(cl), dt_(dt), x_{start, start, start, start}, scale_(16 * DBL_EPSILON * (std::abs(cl.min) + (cl.max - cl.min))) {}

  ::testing::AssertionResult operator()(const Limiter& limiter) {
    const double out = limiter.last()[0];
    x_ = {x_[1], x_[2], x_[3], out};
    const double v = (x_[3] - x_[2]) / dt_;
    const double a = (x_[3] - 2 * x_[2] + x_[1]) / (dt_ * dt_);
    const double j = (x_[3] - 3 * x_[2] + 3 * x_[1] - x_[0]) / (dt_ * dt_ * dt_);
    const double stop = stopping_point(limiter.state(0), {cl_.max_velocity, cl_.max_acceleration, cl_.max_jerk});
    if (!(out >= cl_.min && out <= cl_.max)) return ::testing::AssertionFailure() << "command " << out << " out of range";
    if (!(std::abs(v) <= cl_.max_velocity * (1 + 1e-9) + scale_ / dt_)) return ::testing::AssertionFailure() << "velocity " << v;
    if (!(std::abs(a) <= cl_.max_acceleration * (1 + 1e-9) + 4 * scale_ / (dt_ * dt_)))
      return ::testing::AssertionFailure() << "acceleration " << a;
    if (!(std::abs(j) <= cl_.max_jerk * (1 + 1e-9) + 8 * scale_ / (dt_ * dt_ * dt_))) return ::testing::AssertionFailure() << "jerk " << j;
    // Braking from the state may pass the range by what the solve leaves (it accepts a residual
    // of a few dozen rounding steps of the distances involved and shifts the plan onto the goal
    // by it); the command itself never leaves the range (checked exactly above).
    if (!(stop >= cl_.min - 64 * scale_ && stop <= cl_.max + 64 * scale_)) {
      const MotionState& m = limiter.state(0);
      return ::testing::AssertionFailure() << "braking stops at " << stop << " from p " << m.p << " v " << m.v << " a " << m.a
                                           << ", range [" << cl_.min << ", " << cl_.max << "], goal " << limiter.heading(0)
                                           << ", V A J " << cl_.max_velocity << " " << cl_.max_acceleration << " " << cl_.max_jerk;
    }
    return ::testing::AssertionSuccess();
  }

 private:
  ChannelLimits cl_;
  double dt_;
  std::vector<double> x_;
  double scale_;
};

/// Feeds target(k) for ticks k = 0 .. n-1, checking every command.
template <class Target>
::testing::AssertionResult follow(Limiter& limiter, LimitChecker& check, int n, Target target) {
  std::vector<double> out(1);
  for (int k = 0; k < n; ++k) {
    EXPECT_EQ(limiter.apply(std::vector<double>{target(k)}, out), Status::ok);
    if (::testing::AssertionResult ok = check(limiter); !ok) return ok << " at tick " << k;
  }
  return ::testing::AssertionSuccess();
}

/// Holds `target` until the channel is at rest exactly on `goal`, checking every command;
/// `ticks` counts the ticks taken, `furthest` (if given) tracks the largest command.
::testing::AssertionResult hold_until_at_rest(Limiter& limiter, LimitChecker& check, double target, double goal, int& ticks,
                                              double* furthest = nullptr) {
  std::vector<double> out{limiter.last()[0]};
  for (ticks = 0; !limiter.settled() || out[0] != goal; ++ticks) {
    if (ticks >= 1000000) return ::testing::AssertionFailure() << "not at rest on " << goal;
    EXPECT_EQ(limiter.apply(std::vector<double>{target}, out), Status::ok);
    if (::testing::AssertionResult ok = check(limiter); !ok) return ok << " at tick " << ticks;
    if (furthest != nullptr) *furthest = std::max(*furthest, out[0]);
  }
  return ::testing::AssertionSuccess();
}

// The time-optimal rest-to-rest move of d with limits V, A, J accelerates to a peak velocity vp
// and back: each half is a velocity change of vp taking T1(vp) = vp/A + A/J when A is reached
// (vp >= A²/J), else 2 sqrt(vp/J), and covering vp T1/2 (its velocity is point-symmetric about
// its middle). So:
//  - V and A reached (V >= A²/J, d >= V (V/A + A/J)): T = d/V + V/A + A/J;
//  - V reached, not A (V < A²/J, d >= 2 V sqrt(V/J)): T = d/V + 2 sqrt(V/J);
//  - A reached, not V (2A³/J² <= d < V (V/A + A/J)): d = vp²/A + vp A/J gives
//    T = 2 T1 = A/J + sqrt(A²/J² + 4d/A);
//  - neither (d <= 2A³/J², d < 2 V sqrt(V/J)): d = 2 vp^(3/2)/sqrt(J) gives T = 4 (d/(2J))^(1/3).
// The limiter reaches the goal in the tick in which the plan ends: ceil(T/dt) ticks.
struct RestToRestCase {
  const char* regime;
  double V, A, J, d, optimal_s;
};

TEST(Limiter, RestToRestMovesTakeTheTimeOptimalTime) {
  const double dt = 0.001;
  const RestToRestCase cases[] = {
      {"V and A reached", 2, 10, 100, 5, 5.0 / 2 + 2.0 / 10 + 10.0 / 100},
      {"V reached, not A", 2, 10, 20, 5, 5.0 / 2 + 2 * std::sqrt(2.0 / 20)},
      {"A reached, not V", 2, 10, 100, 0.4, 0.1 + std::sqrt(0.01 + 4 * 0.4 / 10)},
      {"neither reached", 2, 10, 100, 0.1, 4 * std::cbrt(0.1 / 200)},
  };
  for (const RestToRestCase& c : cases) {
    for (double direction : {1.0, -1.0}) {
      SCOPED_TRACE(std::string(c.regime) + (direction > 0 ? ", forward" : ", backward"));
      const ChannelLimits cl{-10, 10, c.V, c.A, c.J, 0};
      Limiter limiter({cl}, dt);
      limiter.reset(std::vector<double>{1});
      LimitChecker check(cl, dt, 1);
      int ticks = 0;
      ASSERT_TRUE(hold_until_at_rest(limiter, check, 1 + direction * c.d, 1 + direction * c.d, ticks));
      std::printf("rest-to-rest %-17s %-8s: %d ticks = %.3f s, optimal %.4f s\n", c.regime, direction > 0 ? "forward" : "backward",
                  ticks, ticks * dt, c.optimal_s);
      EXPECT_GE(ticks * dt, c.optimal_s - 1e-9);
      EXPECT_LE(ticks * dt, c.optimal_s + 2 * dt);
    }
  }
}

TEST(Limiter, ReversalMidMoveStaysWithinLimitsAndTakesTheOptimalTime) {
  // V = 2, A = 10, J = 100 at 1 kHz, from 0 toward 5: after 0.3 s of acceleration (covering
  // V (V/A + A/J)/2 = 0.3) it cruises; at t = 1 s (p = 0.3 + 0.7 V = 1.7) the target becomes -3.
  // The optimal plan changes the velocity from V to -V (2V/A + A/J = 0.5 s, covering 0 by
  // symmetry), cruises at -V, then stops (V/A + A/J = 0.3 s, covering -0.3): the cruise covers
  // -4.7 + 0.3 = -4.4 in 2.2 s, 3.0 s in all. It turns before its braking point, 1.7 + 0.3.
  const double dt = 0.001;
  const ChannelLimits cl{-10, 10, 2, 10, 100, 0};
  Limiter limiter({cl}, dt);
  LimitChecker check(cl, dt, 0);
  ASSERT_TRUE(follow(limiter, check, 1000, [](int) { return 5.0; }));
  EXPECT_NEAR(limiter.last()[0], 1.7, 1e-9);
  double furthest = limiter.last()[0];
  int ticks = 0;
  ASSERT_TRUE(hold_until_at_rest(limiter, check, -3, -3, ticks, &furthest));
  EXPECT_LE(furthest, 2.0);
  EXPECT_GT(furthest, 1.9);
  EXPECT_GE(ticks * dt, 3.0 - 1e-9);
  EXPECT_LE(ticks * dt, 3.0 + 2 * dt);
}

TEST(Limiter, TargetFasterThanTheLimitsIsFollowedWithinThemAndHeldTargetIsReached) {
  // A 3 Hz sine of amplitude 4 asks for 75 units/s; the channel allows 2.
  const double dt = 0.002;
  const ChannelLimits cl{-5, 5, 2, 10, 100, 0.5};
  Limiter limiter({cl}, dt);
  LimitChecker check(cl, dt, 0);
  ASSERT_TRUE(follow(limiter, check, 2000, [&](int k) { return 4 * std::sin(2 * M_PI * 3 * k * dt); }));
  int ticks = 0;
  ASSERT_TRUE(hold_until_at_rest(limiter, check, 3.25, 3.25, ticks));
  EXPECT_GT(limiter.max_lag(0), 0.5);
  EXPECT_EQ(limiter.heading(0), 3.25);
}

TEST(Limiter, ChannelsAreIndependentAndNotDelayed) {
  // A step that one tick's motion can nearly cover with very different limits: each channel
  // starts moving on the first tick, with no padding delay.
  Limiter limiter({{0, 10, 5, 20, 100, 0}, {0, 10, 50, 2000, 1e5, 0}}, 0.01);
  std::vector<double> out(2);
  EXPECT_EQ(limiter.apply(std::vector<double>{0.04, 0.04}, out), Status::ok);
  EXPECT_GT(out[0], 0);
  EXPECT_GT(out[1], 0);
  EXPECT_NEAR(out[0], 100 * 1e-6 / 6, 1e-15);  // J dt³/6: the jerk phase's first tick
  int settled_at = -1;
  for (int k = 1; k < 300 && settled_at < 0; ++k) {
    EXPECT_EQ(limiter.apply(std::vector<double>{0.04, 0.04}, out), Status::ok);
    if (out[1] == 0.04 && limiter.state(1).v == 0) settled_at = k;
  }
  EXPECT_GE(settled_at, 0);
  EXPECT_LT(settled_at, 10);  // the fast channel: 4 (d/(2J))^(1/3) = 0.023 s
}

TEST(JerkProfile, ReplanningFromAStateOnThePlanGivesTheSamePlan) {
  // Bellman: the rest of an optimal plan is the optimal plan from where it has got to.
  const JerkLimits limits{2, 10, 100};
  const MotionState starts[] = {{0, 0, 0}, {0, 1.5, -5}, {0, -1.8, 10}, {0, 2, 0}, {0, 0.3, 9}};
  for (const MotionState& start : starts) {
    for (double goal : {3.0, 0.05, -0.4, -4.0}) {
      SCOPED_TRACE("from v " + std::to_string(start.v) + " a " + std::to_string(start.a) + " to " + std::to_string(goal));
      JerkProfile plan;
      plan.plan(start, goal, limits);
      const MotionState end = plan.at(plan.duration());
      EXPECT_EQ(end.p, goal);
      EXPECT_EQ(end.v, 0);
      for (double t : {0.013, 0.1, 0.37, 0.9}) {
        if (t >= plan.duration()) continue;
        JerkProfile again;
        again.plan(plan.at(t), goal, limits, plan.peak_velocity());
        // (The time left is a square root of rounding-sized quantities near the end.)
        EXPECT_NEAR(again.duration(), plan.duration() - t, 1e-7) << "t " << t;
        EXPECT_NEAR(again.at(0.01).p, plan.at(t + 0.01).p, 1e-9) << "t " << t;
      }
    }
  }
}

TEST(JerkProfile, SolveStopsWhenThePeakVelocityStopsChanging) {
  // States met by the 32-channel bench (V 400, A 4000, J 80000; targets moving every tick) whose
  // root lies next to the natural velocity: the refinement in u = sqrt(|vp - natural|) kept
  // moving u while vp no longer changed, with a residual one rounding step above tolerance, and
  // ran to its bound of 64 evaluations (then settled for a non-optimal bracket end).
  const JerkLimits limits{400, 4000, 80000};
  struct Case {
    MotionState from;
    double goal;
  };
  const Case cases[] = {
      {{-0x1.2a6c4508ef7d5p+1, -0x1.834556db66094p+6, 0x1.2bc15acba8066p+5}, -0x1.6fd844d1d0844p+2},
      {{0x1.14f2501c28569p+3, 0x1.5001f21d3123ep+8, -0x1.11e8aebcc3987p+5}, 0x1.f53f3db41e188p+4},
      {{-0x1.b825188d778d8p+2, -0x1.013eefe8854bp+8, 0x1.1e042e243773dp+5}, -0x1.5b3c6a424114cp+4},
      {{-0x1.14f0885c5cf46p+3, -0x1.500538a587e43p+8, 0x1.11d341a07137bp+5}, -0x1.f54444989fbd4p+4},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("from p " + std::to_string(c.from.p) + " v " + std::to_string(c.from.v) + " to " + std::to_string(c.goal));
    JerkProfile plan;
    plan.plan(c.from, c.goal, limits);
    EXPECT_LE(plan.evaluations(), 12);
    const MotionState end = plan.at(plan.duration());
    EXPECT_EQ(end.p, c.goal);
    // On the plan: its start is the state, and a re-plan from a point on it agrees.
    EXPECT_NEAR(plan.at(0).p, c.from.p, 1e-12);
    JerkProfile again;
    again.plan(plan.at(0.001), c.goal, limits, plan.peak_velocity());
    EXPECT_NEAR(again.duration(), plan.duration() - 0.001, 1e-7);
    EXPECT_LE(again.evaluations(), 12);
  }
}

TEST(JerkProfile, RestToRestPeakIsThePlansPeak) {
  // In each regime of the rest-to-rest move (V and A reached, V only, A only, neither), the closed
  // form is the solved peak, so a plan from rest that starts from it takes one evaluation.
  const JerkLimits limits{2, 10, 100};
  for (double d : {5.0, 0.5, 0.4, 0.1, 1e-6, -0.3, -7.0}) {
    for (const JerkLimits& l : {limits, JerkLimits{2, 10, 20}}) {
      SCOPED_TRACE("d " + std::to_string(d) + " J " + std::to_string(l.jerk));
      JerkProfile solved;
      solved.plan({1, 0, 0}, 1 + d, l, 0);
      const double peak = rest_to_rest_peak(d, l);
      EXPECT_NEAR(peak, solved.peak_velocity(), 1e-12 * std::max(1.0, std::abs(peak)));
      JerkProfile started;
      started.plan({1, 0, 0}, 1 + d, l, peak);
      EXPECT_LE(started.evaluations(), 2);
      EXPECT_EQ(started.at(started.duration()).p, 1 + d);
    }
  }
}

TEST(JerkProfile, StatesWhereEveryChannelTurnsAtOncePlanInFewEvaluations) {
  // States of the 32-channel bench rig at the ticks that cost most (homing hands over to the
  // show): braking onto a goal just ahead (root next to 0, found by the braking model), a hint
  // on the corner at the natural velocity (Newton in u from the corner), and a goal that starts
  // moving back (root beyond 0, the probe then one Newton step). Evaluations before: 6, 8, 6.
  const JerkLimits limits{400, 4000, 80000};
  const PlanSlack slack{6e-8, 0.002};
  struct Case {
    MotionState from;
    double goal;
    double hint;
    int evaluations;
  };
  const Case cases[] = {
      {{-0x1.dffefcd22d16ep+5, -0x1.4cde43edb2414p-2, 0x1.9035997ade6fdp+5}, -0x1.ep+5, -0.34070798656625606, 4},
      {{-0x1.97361f53fbee3p+4, -0x1.49948f876679fp-5, 0x1.e9a855a6e8a32p+5}, -0x1.97363b9b9ba9p+4, -0.016817467848897809, 3},
      {{0x1.8f803c994300ep+4, 0x1.7e73aeba4cf68p-7, -0x1.950e492963a3cp+4}, 0x1.8f7d39a7ad9f4p+4, 0.015677125496682851, 5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("goal " + std::to_string(c.goal));
    JerkProfile plan;
    plan.plan(c.from, c.goal, limits, c.hint, slack);
    EXPECT_LE(plan.evaluations(), c.evaluations);
    JerkProfile exact;
    exact.plan(c.from, c.goal, limits);
    // Within its slack of the exact plan: the tick it is followed for barely differs.
    EXPECT_NEAR(plan.at(0.001).p, exact.at(0.001).p, 1e-9);
    EXPECT_NEAR(plan.at(plan.duration()).p, c.goal, slack.distance);
  }
}

TEST(JerkProfile, SlackLetsLongPlansEndNearTheGoalAndShortOnesExactly) {
  const JerkLimits limits{400, 4000, 80000};
  const MotionState from{0, 120, -900};
  const double slack = 1e-7;
  for (double goal : {30.0, -12.0, 1.2, 0.3}) {
    SCOPED_TRACE("goal " + std::to_string(goal));
    JerkProfile exact, loose;
    exact.plan(from, goal, limits, 0);
    loose.plan(from, goal, limits, 0, {slack, 0.002});
    // The first tick barely differs from the exact plan's; the end lies within the slack.
    EXPECT_NEAR(loose.at(0.001).p, exact.at(0.001).p, 1e-9);
    EXPECT_NEAR(loose.at(loose.duration() - 1e-9).p, goal, 2 * slack);
    EXPECT_LE(loose.evaluations(), exact.evaluations());
    // A plan ending within `after` is solved to rounding and lands exactly.
    JerkProfile short_plan;
    short_plan.plan(from, goal, limits, 0, {slack, 10.0});
    EXPECT_EQ(short_plan.at(short_plan.duration()).p, goal);
    EXPECT_NEAR(short_plan.at(0.001).p, exact.at(0.001).p, 1e-12);
  }
}

/// A seeded family of plans for limits {400, 4000, 80000}: states that can keep |v| <= V (see
/// JerkProfile), with goals up to 60 units away. Failures name the seed.
class PlanFamily {
 public:
  explicit PlanFamily(unsigned seed) : rng_(seed), trace_(__FILE__, __LINE__, "seed " + std::to_string(seed)) {}
  std::pair<MotionState, double> next() {
    const double a = 4000 * uniform();
    const double v_room = 400 - 0.5 * a * a / 80000;
    const MotionState from{10 * uniform(), v_room * uniform(), a};
    return {from, from.p + 60 * uniform()};
  }
  double uniform() { return u_(rng_); }  ///< in [-1, 1]

 private:
  std::mt19937 rng_;
  std::uniform_real_distribution<double> u_{-1, 1};
  ::testing::ScopedTrace trace_;
};

TEST(JerkProfile, ANearHintOnALongPlanCostsOneEvaluationAndStillEndsWithinTheSlack) {
  // A hint a little off the root (a target that moved a little) on a plan that outlasts the
  // slack's horizon: one step, its residual predicted by Taylor and not evaluated. Over a seeded
  // family of states and goals, for hints off by up to 1e-6, 1e-4 and 1e-3 of the peak: the
  // plan's end stays within the slack of the goal, its first tick next to the exact plan's, and
  // nearly all such plans take that one evaluation.
  const JerkLimits limits{400, 4000, 80000};
  const double slack = 1e-7;
  for (const double off : {1e-6, 1e-4, 1e-3}) {
    PlanFamily family(77);
    int long_plans = 0, one_evaluation = 0;
    for (int i = 0; i < 20000; ++i) {
      const auto [from, goal] = family.next();
      JerkProfile exact;
      exact.plan(from, goal, limits, 0);
      if (!(exact.duration() > 0.01)) continue;
      const double hint = exact.peak_velocity() * (1 + off * family.uniform());
      // (A hint across the natural velocity or 0 from the peak starts on another branch, where D
      // need not be monotone: the solve may find another root there, a valid plan but another.)
      const double natural = from.v + 0.5 * from.a * std::abs(from.a) / limits.jerk, peak = exact.peak_velocity();
      if ((hint - natural) * (peak - natural) <= 0 || hint * peak <= 0) continue;
      ++long_plans;
      JerkProfile loose;
      loose.plan(from, goal, limits, hint, {slack, 0.002});
      ASSERT_NEAR(loose.at(loose.duration() - 1e-12).p, goal, 2 * slack) << "case " << i << ", off by " << off;
      ASSERT_NEAR(loose.at(0.001).p, exact.at(0.001).p, 1e-9) << "case " << i << ", off by " << off;
      ASSERT_LE(std::abs(loose.peak_velocity()), limits.velocity);
      one_evaluation += loose.evaluations() == 1;
    }
    EXPECT_GT(long_plans, 10000);
    // 93%, 93% and 89% (93%, 45% and 12% with a Newton step: its D'' step²/2 is within the slack
    // only for the nearest hints, where the second-order step's D''' step³/6 is for most).
    EXPECT_GT(one_evaluation, long_plans * (off > 1e-4 ? 85 : 90) / 100) << one_evaluation << " of " << long_plans << ", off by " << off;
  }
}

TEST(JerkProfile, PeakSensitivityGivesTheNextPlansPeakWhenTheGoalMoves) {
  // From the state a tick along a plan, toward a goal that moved by g: while that state is before
  // its change's fall, the second-order step by g from the plan's D' and D'' lands next to the new
  // plan's peak (its error is third order in g). Over a seeded family of plans and moves.
  PlanFamily family(91);
  const JerkLimits limits{400, 4000, 80000};
  const double dt = 0.001;
  int before_fall = 0, close = 0, known = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto [from, goal] = family.next();
    JerkProfile plan;
    plan.plan(from, goal, limits, 0);
    const PeakSensitivity d = plan.peak_sensitivity(dt);
    if (!std::isfinite(d.slope)) continue;
    ++known;
    ASSERT_GT(d.slope, 0) << "case " << i;
    const double g = 0.05 * family.uniform();  // a goal moving up to 50 units/s
    JerkProfile moved;
    moved.plan(plan.at(dt), goal + g, limits, 0);
    const double vp = plan.peak_velocity(), next = moved.peak_velocity();
    if (!d.before_fall || std::abs(next) >= limits.velocity) continue;
    ++before_fall;
    const double guess = moved_goal_peak(d, vp, g);
    close += std::abs(guess - next) <= 1e-3 * std::abs(next - vp) + 1e-12 * limits.velocity;
  }
  EXPECT_GT(known, 10000);
  EXPECT_GT(before_fall, 5000);
  EXPECT_GT(close, before_fall * 99 / 100) << close << " of " << before_fall;
}

TEST(Limiter, EveryPlanOfAMovingTargetStaysWithinTheEvaluationBound) {
  // Many channels chasing waves of different speeds and a jump: the cost observable never exceeds
  // the documented bound, and on average a moving target costs a few evaluations.
  const double dt = 0.001;
  std::vector<ChannelLimits> limits(16, ChannelLimits{-90, 90, 400, 4000, 80000, 0});
  Limiter limiter(limits, dt);
  std::vector<double> target(16), out(16);
  long total = 0, plans = 0;
  int worst = 0;
  for (int k = 0; k < 20000; ++k) {
    for (std::size_t i = 0; i < target.size(); ++i) {
      const double w = 2 + 1.7 * static_cast<double>(i);
      target[i] = 60 * std::cos(static_cast<double>(i)) * std::sin(w * k * dt) + (k % 4000 < 2000 ? 10.0 : -10.0);
    }
    EXPECT_EQ(limiter.apply(target, out), Status::ok);
    for (std::size_t i = 0; i < target.size(); ++i) {
      const int e = limiter.evaluations(i);
      worst = std::max(worst, e);
      total += e;
      plans += e > 0;
    }
  }
  EXPECT_LE(worst, JerkProfile::kMaxEvaluations);
  EXPECT_LE(worst, 40) << "a plan took " << worst << " evaluations";
  EXPECT_LT(static_cast<double>(total) / static_cast<double>(plans), 8.0);
}

TEST(Limiter, AGoalThatEasesOutOfRestAndBackToRestIsFollowedCheaplyAtBothEnds) {
  // Every channel's goal leaves rest along a half-cosine at once, and comes to rest at once (as
  // homing did before it glided). Here the first plans end within a tick or two, before the
  // plans from rest stop sharing their start. The peaks of the first plans grow about 2.3x a
  // tick; guessing each from the last one cost 4-6 evaluations a plan. At the end every plan's peak collapses toward zero as its goal stops:
  // up to 52 (62 on the slower ramp) evaluations a tick for 16 channels, before a plan that brakes
  // with its run of peaks broken was guessed as a turn near rest; and up to 43 in the first ticks
  // of the slower ramp, before that guess was kept for goals that slow down.
  const double dt = 0.001;
  const std::size_t n = 16;
  std::vector<ChannelLimits> limits(n, ChannelLimits{-90, 90, 400, 4000, 80000, 0});
  for (const auto& [duration, at_end] : {std::pair{1.5, 42}, std::pair{2.357, 54}}) {
    SCOPED_TRACE("ramp of " + std::to_string(duration) + " s");
    Limiter limiter(limits, dt);
    std::vector<double> target(n), out(n);
    for (int k = 1; k <= static_cast<int>(duration / dt) + 200; ++k) {
      const double t = std::min(k * dt, duration);
      for (std::size_t i = 0; i < n; ++i) {
        const double distance = 60 * std::cos(static_cast<double>(i) + 0.5);
        target[i] = 0.5 * distance * (1 - std::cos(M_PI * t / duration));
      }
      EXPECT_EQ(limiter.apply(target, out), Status::ok);
      int total = 0;
      for (std::size_t i = 0; i < n; ++i) total += limiter.evaluations(i);
      if (k <= 12) {
        EXPECT_LE(total, 40) << "tick " << k;
      }
      if (k * dt >= duration - 0.1) {
        EXPECT_LE(total, at_end) << "tick " << k;
      }
    }
  }
}

TEST(Limiter, AKeyWhereEveryGoalChangesItsAccelerationAtOnceCostsLittleMore) {
  // Keys every 0.5 s alternating between -+amplitude, eased between them: at each key every
  // channel's goal switches from braking to the next segment's start at once, as at a show's keys
  // and where it loops. Guessed from the peaks' history, the ticks after a key took 33-38
  // evaluations for 16 channels (against about 20 between keys); the step by the goal's own move
  // from the last plan's D' and D'' takes at most 27.
  const double dt = 0.001;
  const std::size_t n = 16;
  std::vector<ChannelLimits> limits(n, ChannelLimits{-90, 90, 400, 4000, 80000, 0});
  Limiter limiter(limits, dt);
  std::vector<double> target(n), out(n);
  const auto wave = [](double amplitude, double t) {
    const double segment = std::floor(t / 0.5), s = t / 0.5 - segment;
    const double from = std::fmod(segment, 2) == 0 ? -amplitude : amplitude;
    return from - 2 * from * s * s * (3 - 2 * s);
  };
  const auto set_targets = [&](int k) {
    for (std::size_t i = 0; i < n; ++i) target[i] = wave(60 * std::cos(static_cast<double>(i) + 0.5), k * dt);
  };
  set_targets(0);
  limiter.reset(target);
  for (int k = 1; k <= 3000; ++k) {
    set_targets(k);
    EXPECT_EQ(limiter.apply(target, out), Status::ok);
    if (k < 500 || k % 500 == 0 || k % 500 > 3) continue;
    int total = 0;
    for (std::size_t i = 0; i < n; ++i) total += limiter.evaluations(i);
    EXPECT_LE(total, 30) << "tick " << k;
  }
}

TEST(Limiter, AGlideBringsEveryChannelToItsGoalTogetherOnTheSmoothestMoveFromOnePlan) {
  // Three channels, distances 60, 6 and 0.3 at peak speeds 40, 100 and 100: the first sets the
  // duration (2 * 60 / 40 = 3 s), the others glide slower to arrive with it.
  const double dt = 0.001;
  const std::vector<ChannelLimits> limits(3, ChannelLimits{-90, 90, 400, 4000, 80000, 0});
  Limiter limiter(limits, dt);
  limiter.reset(std::vector<double>{0, 10, -5});
  const std::vector<double> goal{60, 4, -5.3}, peak_speed{40, 100, 100};
  const double duration = limiter.glide_duration(goal, peak_speed, 0.25);
  EXPECT_DOUBLE_EQ(duration, 3.0);
  EXPECT_DOUBLE_EQ(limiter.glide_duration(goal, peak_speed, 5.0), 5.0);  // never below the minimum
  limiter.glide_to(goal, duration);
  std::vector<double> out(3);
  std::vector<std::vector<double>> samples{{0}, {10}, {-5}};
  int ticks = 0, evaluations = 0, worst = 0;
  for (; (ticks == 0 || !limiter.settled()) && ticks < 5000; ++ticks) {
    EXPECT_EQ(limiter.apply(goal, out), Status::ok);
    for (std::size_t i = 0; i < 3; ++i) {
      evaluations += limiter.evaluations(i);
      worst = std::max(worst, limiter.evaluations(i));
      EXPECT_TRUE(limiter.gliding(i));
      samples[i].push_back(out[i]);
    }
  }
  // Arrived together, at the glide's end (to the tick), exactly on the goals.
  EXPECT_GE(ticks, 3000);
  EXPECT_LE(ticks, 3001);
  EXPECT_EQ(out, goal);
  // Planned once, on the first tick (exact, from rest), then followed toward the held goal.
  EXPECT_EQ(evaluations, 3);
  EXPECT_EQ(worst, 1);
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE("channel " + std::to_string(i));
    const double d = std::abs(goal[i] - samples[i].front());
    double speed = 0, acceleration = 0, jerk = 0;
    for (std::size_t k = 3; k < samples[i].size(); ++k) {
      const double* x = &samples[i][k - 3];
      speed = std::max(speed, std::abs(x[3] - x[2]) / dt);
      acceleration = std::max(acceleration, std::abs(x[3] - 2 * x[2] + x[1]) / (dt * dt));
      jerk = std::max(jerk, std::abs(x[3] - 3 * x[2] + 3 * x[1] - x[0]) / (dt * dt * dt));
    }
    // Speed 2d/T and acceleration 8d/T² at their peaks, jerk 32d/T³ throughout: the smoothest
    // rest-to-rest move of that duration (a sample's differences straddle the peaks: within a tick).
    EXPECT_NEAR(speed, 2 * d / duration, 1e-3 * d + 1e-9);
    EXPECT_NEAR(acceleration, 8 * d / (duration * duration), 1e-2 * d + 1e-6);
    EXPECT_LE(jerk, 32 * d / (duration * duration * duration) * (1 + 1e-6) + 1e-3);
  }
  // A new target ends the glide: the channel's own limits apply again at once.
  std::vector<double> away{60, 4, 5};
  EXPECT_EQ(limiter.apply(away, out), Status::ok);
  EXPECT_FALSE(limiter.gliding(2));
  EXPECT_TRUE(limiter.gliding(0));  // (still on its glide's goal)
  for (int k = 0; k < 200; ++k) EXPECT_EQ(limiter.apply(away, out), Status::ok);
  EXPECT_DOUBLE_EQ(out[2], 5.0);  // 10.3 units in 0.2 s: at the glide's jerk it would take 2.4 s
}

TEST(Limiter, WarmingChangesNothingThatApplyDoes) {
  // warm() makes and drops the first plans (cache only): the commands are bit for bit those of a
  // limiter that was not warmed, gliding or not, and channels in motion are left alone.
  const std::vector<ChannelLimits> limits(3, ChannelLimits{-90, 90, 400, 4000, 80000, 0});
  Limiter warmed(limits, 0.001), cold(limits, 0.001);
  const std::vector<double> start{0, 10, -5}, goal{60, 4, -5}, next{-20, 30, 7};
  for (Limiter* l : {&warmed, &cold}) {
    l->reset(start);
    l->glide_to(goal, 2.0);
  }
  warmed.warm(goal);
  std::vector<double> a(3), b(3);
  for (int k = 0; k < 3000; ++k) {
    const std::vector<double>& target = k < 500 ? goal : next;
    if (k == 500) warmed.warm(next);  // (in motion: nothing to do)
    EXPECT_EQ(warmed.apply(target, a), Status::ok);
    EXPECT_EQ(cold.apply(target, b), Status::ok);
    ASSERT_EQ(a, b) << "tick " << k;
  }
}

TEST(Limiter, ATargetLeavingRestIsFollowedAtOneEvaluationAPlanWhileItsPlansShareTheirStart) {
  // Every time-optimal plan from rest in one direction starts alike, so while the state is still
  // on that start the next plan's peak is the rest-to-rest move's from where the channel left
  // rest. Guessed from the peaks' history, the plans that follow a target easing out of rest
  // (as a show starts from a held pose) cost two or three evaluations each.
  const double dt = 0.001;
  for (const double acceleration : {1000.0, 4000.0, 20000.0}) {
    SCOPED_TRACE("target acceleration " + std::to_string(acceleration));
    Limiter limiter({ChannelLimits{-90, 90, 400, 4000, 80000, 0}}, dt);
    std::vector<double> target(1), out(1);
    for (int k = 1; k <= 4; ++k) {
      target[0] = 0.5 * acceleration * (k * dt) * (k * dt);
      EXPECT_EQ(limiter.apply(target, out), Status::ok);
      EXPECT_EQ(limiter.evaluations(0), 1) << "tick " << k;
    }
  }
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
    LimitChecker check_limits(cl, dt, limiter.last()[0]);
    const auto check = [&](int tick) { ASSERT_TRUE(check_limits(limiter)) << "family " << family << " tick " << tick; };
    double target = 0;
    const int segments = 1 + static_cast<int>(rng() % 6);
    int tick = 0;
    for (int k = 0; k < segments; ++k) {
      target = u(rng) < 0.05 ? std::numeric_limits<double>::quiet_NaN() : min - 0.5 * range + 2 * range * u(rng);
      const int hold = 1 + static_cast<int>(rng() % 40);
      for (int h = 0; h < hold; ++h, ++tick) {
        EXPECT_EQ(limiter.apply(std::span<const double>(&target, 1), out), std::isnan(target) ? Status::not_finite : Status::ok);
        check(tick);
        if (HasFatalFailure()) return;
      }
    }
    if (std::isnan(target)) target = min;
    const double margin = std::min(cl.soft_margin, range / 2);
    const double goal = std::clamp(target, cl.min + margin, cl.max - margin);
    for (int h = 0; !(limiter.settled() && out[0] == goal); ++h, ++tick) {
      EXPECT_EQ(limiter.apply(std::span<const double>(&target, 1), out), Status::ok);
      check(tick);
      if (HasFatalFailure()) return;
      // At most: a stop, then a move across the range.
      const double bound_s = range / cl.max_velocity + 2 * (cl.max_velocity / cl.max_acceleration + cl.max_acceleration / cl.max_jerk);
      ASSERT_LT(h, static_cast<int>(bound_s / dt) + 10) << "family " << family;
    }
  }
}

}  // namespace
}  // namespace avar::control
