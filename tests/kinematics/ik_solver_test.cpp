#include "avar/kinematics/ik_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "avar/kinematics/denavit_hartenberg.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

using Goals = std::vector<IkGoal>;

std::string seed_text(std::uint64_t seed) { return "seed " + std::to_string(seed); }

void expect_within_limits(const Model& m, const std::vector<double>& q) {
  for (std::size_t k = 0; k < q.size(); ++k) {
    EXPECT_TRUE(std::isfinite(q[k])) << "joint " << k;
    EXPECT_GE(q[k], m.lower_limits()[k]) << "joint " << k;
    EXPECT_LE(q[k], m.upper_limits()[k]) << "joint " << k;
  }
}

Eigen::Isometry3d pose_at(const Model& m, const std::vector<double>& q, std::size_t effector) {
  Workspace ws(m);
  EXPECT_EQ(forward_kinematics(m, q, ws), Status::ok);
  return effector_pose(m, ws, effector);
}

/// The truth perturbed by up to +-spread per joint, clamped to the limits.
std::vector<double> near(const Model& m, const std::vector<double>& truth, double spread, std::mt19937_64& rng) {
  std::vector<double> q = truth;
  for (std::size_t k = 0; k < q.size(); ++k)
    q[k] = std::clamp(q[k] + test::uniform(rng, -spread, spread), m.lower_limits()[k], m.upper_limits()[k]);
  return q;
}

IkOptions with_method(IkMethod method, int max_iterations = 100) {
  IkOptions options = default_ik_options();
  options.method = method;
  options.max_iterations = max_iterations;
  return options;
}

/// Two revolute joints about z, links l1 = 0.3 and l2 = 0.2 along x, the hand at the end.
Model planar_two_link() {
  ModelBuilder b;
  b.add_joint({"shoulder", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_joint({"elbow", JointType::revolute, "shoulder", test::translation(0.3, 0, 0), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_effector({"hand", "elbow", test::translation(0.2, 0, 0)});
  return b.build();
}

/// Solves `samples` random reachable poses of each reference arm from `start(model, truth, rng)`
/// with `options`; checks limits and, for converged solves, the reached pose; expects at least
/// `required_percent` of them to converge.
class IkBenchChains : public test::BenchChains {
 protected:
  template <typename Start>
  void expect_round_trips(std::uint64_t seed, int samples, int required_percent, const IkOptions& options, Start start) {
    for (const DhChain& chain : chains) {
      SCOPED_TRACE(chain.name + ", " + seed_text(seed));
      std::mt19937_64 rng(seed);
      const Model m = chain_from_standard_dh(chain.rows);
      IkWorkspace ik(m);
      int converged = 0;
      for (int sample = 0; sample < samples; ++sample) {
        const std::vector<double> truth = test::random_configuration(m, rng);
        const std::vector<double> seed_q = start(m, truth, rng);
        const Goals goals{IkGoal::at_pose(0, pose_at(m, truth, 0))};
        std::vector<double> out(m.dof());
        const IkResult r = solve_ik(m, ik, goals, seed_q, out, options);
        expect_within_limits(m, out);
        if (r.status != IkStatus::converged) continue;
        ++converged;
        const Eigen::Isometry3d reached = pose_at(m, out, 0);
        EXPECT_LT((reached.translation() - goals[0].position).cwiseAbs().maxCoeff(), 1e-5) << "sample " << sample;
        EXPECT_LT(Eigen::AngleAxisd(reached.linear() * goals[0].orientation.toRotationMatrix().transpose()).angle(), 2e-5)
            << "sample " << sample;
        EXPECT_LE(r.position_error, 1e-5);
        EXPECT_LE(r.orientation_error, 1e-5);
      }
      EXPECT_GE(converged * 100, samples * required_percent);
    }
  }
};

TEST_F(IkBenchChains, DefaultSolverTracksRandomPosesOfTheReferenceArms) {
  expect_round_trips(20261201, 300, 99, default_ik_options(),
                     [](const Model& m, const std::vector<double>& truth, std::mt19937_64& rng) { return near(m, truth, 0.3, rng); });
}

TEST_F(IkBenchChains, ColdStartWithRestartsReachesRandomPosesFromTheZeroPose) {
  expect_round_trips(7, 100, 98, cold_start_ik_options(),
                     [](const Model& m, const std::vector<double>&, std::mt19937_64&) { return std::vector<double>(m.dof(), 0.0); });
}

TEST_F(IkBenchChains, WarmStartedTicksFollowAPathWithSmallJointSteps) {
  // A circle of 0.08 m radius traced in 500 ticks with a fixed hand orientation, each tick seeded
  // with the previous tick's answer, as the control loop does. The start bends every joint
  // (1.2, -1.5, ...), well inside the workspace and away from the arms' singular stretched and
  // wrist-aligned poses.
  for (const DhChain& chain : chains) {
    SCOPED_TRACE(chain.name);
    const Model m = chain_from_standard_dh(chain.rows);
    IkWorkspace ik(m);
    std::vector<double> q(m.dof()), next(m.dof());
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = k % 2 == 0 ? 1.2 : -1.5;
    const Eigen::Isometry3d start = pose_at(m, q, 0);
    for (int tick = 0; tick <= 500; ++tick) {
      const double angle = 2 * std::numbers::pi * tick / 500;
      Eigen::Isometry3d target = start;
      target.translation() += Eigen::Vector3d(0.08 * (std::cos(angle) - 1), 0.08 * std::sin(angle), 0);
      const IkResult r = solve_ik(m, ik, Goals{IkGoal::at_pose(0, target)}, q, next);
      ASSERT_EQ(r.status, IkStatus::converged) << "tick " << tick << ": " << r.position_error << " m, " << r.orientation_error << " rad, " << r.iterations << " iterations";
      for (std::size_t k = 0; k < q.size(); ++k) EXPECT_LT(std::abs(next[k] - q[k]), 0.1) << "tick " << tick << ", joint " << k;
      q = next;
    }
  }
}

TEST_F(IkBenchChains, OutOfReachTargetStretchesTheArmAndIsDegraded) {
  for (const DhChain& chain : chains) {
    SCOPED_TRACE(chain.name);
    const Model m = chain_from_standard_dh(chain.rows);
    IkWorkspace ik(m);
    const Eigen::Vector3d far(1.5, 1.0, 0.8);  // about 2 m away; neither arm reaches 1.3 m
    std::vector<double> out(m.dof());
    const IkResult r = solve_ik(m, ik, Goals{IkGoal::at_position(0, far)}, std::vector<double>(m.dof(), 0.3), out,
                                cold_start_ik_options());
    EXPECT_EQ(r.status, IkStatus::degraded);
    expect_within_limits(m, out);
    const Eigen::Vector3d reached = pose_at(m, out, 0).translation();
    EXPECT_NEAR(r.position_error, (far - reached).cwiseAbs().maxCoeff(), 1e-9);
    // The closest reachable point lies toward the target: moving it any further along the line
    // of sight is not possible, so the remaining error points along that line.
    EXPECT_GT((far - reached).normalized().dot(far.normalized()), 0.9);
  }
}

TEST(IkSolver, EveryMethodReachesPositionsOfTheBranchedFigureWithinLimits) {
  const std::uint64_t seed = 11;
  const Model m = test::branched_figure();
  const std::size_t hand = *m.find_effector("hand");
  IkWorkspace ik(m);
  for (const IkMethod method : {IkMethod::damped_least_squares, IkMethod::pseudo_inverse, IkMethod::jacobian_transpose,
                                IkMethod::cyclic_coordinate_descent}) {
    SCOPED_TRACE("method " + std::to_string(static_cast<int>(method)) + ", " + seed_text(seed));
    std::mt19937_64 rng(seed);
    int converged = 0;
    const int samples = 50;
    for (int sample = 0; sample < samples; ++sample) {
      const std::vector<double> truth = test::random_configuration(m, rng);
      const Goals goals{IkGoal::at_position(hand, pose_at(m, truth, hand).translation())};
      std::vector<double> out(m.dof());
      const IkResult r = solve_ik(m, ik, goals, near(m, truth, 0.2, rng), out, with_method(method, 5000));
      expect_within_limits(m, out);
      if (r.status == IkStatus::converged) {
        ++converged;
        EXPECT_LT((pose_at(m, out, hand).translation() - goals[0].position).cwiseAbs().maxCoeff(), 1e-5);
      }
    }
    // Transpose and CCD converge slowly near the end; they must still get most of the way.
    EXPECT_GE(converged, samples * 8 / 10);
  }
}

TEST(IkSolver, SeveralEffectorsOnOneTreeAreSolvedTogether) {
  const std::uint64_t seed = 12;
  SCOPED_TRACE(seed_text(seed));
  std::mt19937_64 rng(seed);
  const Model m = test::branched_figure();
  const std::size_t hand = *m.find_effector("hand"), head = *m.find_effector("head");
  IkWorkspace ik(m, 2);
  int converged = 0;
  for (int sample = 0; sample < 50; ++sample) {
    const std::vector<double> truth = test::random_configuration(m, rng);
    const Goals goals{IkGoal::at_position(hand, pose_at(m, truth, hand).translation()),
                      IkGoal::at_position(head, pose_at(m, truth, head).translation(), 2.0)};
    std::vector<double> out(m.dof());
    const IkResult r = solve_ik(m, ik, goals, near(m, truth, 0.2, rng), out);
    expect_within_limits(m, out);
    if (r.status != IkStatus::converged) continue;
    ++converged;
    EXPECT_LT((pose_at(m, out, hand).translation() - goals[0].position).norm(), 2e-5);
    EXPECT_LT((pose_at(m, out, head).translation() - goals[1].position).norm(), 2e-5);
  }
  EXPECT_GE(converged, 48);
}

TEST(IkSolver, UnreachableTargetGivesTheClosestPoseAndDegraded) {
  const Model m = planar_two_link();
  IkWorkspace ik(m);
  const Eigen::Vector3d target(0.6, 0.3, 0);  // 0.67 m away; the arm reaches 0.5 m
  const Goals goals{IkGoal::at_position(0, target)};
  std::vector<double> out(2);
  const IkResult r = solve_ik(m, ik, goals, std::vector<double>{0.3, 0.4}, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  const Eigen::Vector3d closest = target.normalized() * 0.5;
  EXPECT_LT((pose_at(m, out, 0).translation() - closest).norm(), 1e-4);
  EXPECT_NEAR(r.position_error, (target - closest).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(IkSolver, TargetBeyondAJointLimitStopsAtTheLimit) {
  const Model m = planar_two_link();
  IkWorkspace ik(m);
  // Orientation about z of 3.1 rad needs q0 + q1 = 3.1 with the elbow straight: reachable.
  // A position straight behind along -x with the elbow at most 3 rad short of folding: the
  // shoulder must pass its +-3 rad limit to point the straight arm at -x.
  const Goals goals{IkGoal::at_position(0, Eigen::Vector3d(-0.5, 0, 0))};
  std::vector<double> out(2);
  const IkResult r = solve_ik(m, ik, goals, std::vector<double>{2.5, 0.0}, out);
  expect_within_limits(m, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  EXPECT_GT(r.position_error, 1e-3);
}

TEST(IkSolver, RandomGoalsOnRandomTreesNeverLeaveTheLimits) {
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    SCOPED_TRACE(seed_text(seed));
    std::mt19937_64 rng(seed);
    const Model m = test::random_tree(rng, 8);
    IkWorkspace ik(m, 2);
    for (const IkMethod method : {IkMethod::damped_least_squares, IkMethod::pseudo_inverse, IkMethod::jacobian_transpose,
                                  IkMethod::cyclic_coordinate_descent}) {
      for (int sample = 0; sample < 20; ++sample) {
        const Eigen::Isometry3d target = test::random_rigid(rng, 1.0);
        const Goals goals{IkGoal::at_pose(m.effector_count() - 1, target), IkGoal::at_position(0, target.translation())};
        std::vector<double> out(m.dof());
        const IkResult r = solve_ik(m, ik, goals, test::random_configuration(m, rng), out, with_method(method));
        expect_within_limits(m, out);
        EXPECT_GT(r.iterations, 0);
        EXPECT_LE(r.iterations, 101);
      }
    }
  }
}

TEST(IkSolver, OrientationGoalTurnsTheEffectorFrame) {
  const std::uint64_t seed = 31;
  SCOPED_TRACE(seed_text(seed));
  std::mt19937_64 rng(seed);
  const Model m = test::branched_figure();
  const std::size_t hand = *m.find_effector("hand");
  IkWorkspace ik(m);
  const std::vector<double> truth = test::random_configuration(m, rng);
  const Eigen::Quaterniond target(pose_at(m, truth, hand).linear());
  const Goals goals{IkGoal::at_orientation(hand, target)};
  std::vector<double> out(m.dof());
  const IkResult r = solve_ik(m, ik, goals, near(m, truth, 0.2, rng), out);
  ASSERT_EQ(r.status, IkStatus::converged);
  EXPECT_LT(Eigen::AngleAxisd(pose_at(m, out, hand).linear() * target.toRotationMatrix().transpose()).angle(), 2e-5);
}

TEST(IkSolver, AimGoalPointsTheEffectorAxisAtTheTarget) {
  ModelBuilder b;
  b.add_joint({"pan", JointType::revolute, "", test::translation(0, 0, 1), Eigen::Vector3d::UnitZ(), -2, 2});
  b.add_joint({"tilt", JointType::revolute, "pan", test::translation(0, 0, 0.1), Eigen::Vector3d::UnitY(), -1, 1});
  b.add_effector({"eye", "tilt", test::translation(0.05, 0, 0)});
  const Model m = b.build();
  IkWorkspace ik(m);
  for (const IkMethod method : {IkMethod::damped_least_squares, IkMethod::cyclic_coordinate_descent}) {
    const Eigen::Vector3d target(1.0, 0.8, 1.5);
    const Goals goals{IkGoal::aiming(0, Eigen::Vector3d::UnitX(), target)};
    std::vector<double> out(2);
    const IkResult r = solve_ik(m, ik, goals, std::vector<double>{0, 0}, out, with_method(method, 500));
    ASSERT_EQ(r.status, IkStatus::converged) << static_cast<int>(method);
    const Eigen::Isometry3d eye = pose_at(m, out, 0);
    const Eigen::Vector3d sight = (target - eye.translation()).normalized();
    EXPECT_GT((eye.linear() * Eigen::Vector3d::UnitX()).dot(sight), std::cos(1e-5));
  }
}

TEST(IkSolver, PseudoInverseNullSpaceTaskStaysNearThePreferredPose) {
  // Three planar links reaching a point: one redundant degree of freedom.
  ModelBuilder b;
  b.add_joint({"a", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_joint({"b", JointType::revolute, "a", test::translation(0.3, 0, 0), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_joint({"c", JointType::revolute, "b", test::translation(0.3, 0, 0), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_effector({"tip", "c", test::translation(0.3, 0, 0)});
  const Model m = b.build();
  IkWorkspace ik(m);
  const std::vector<double> preferred{0.2, 0.9, 0.9};
  const Goals goals{IkGoal::at_position(0, Eigen::Vector3d(0.4, 0.45, 0))};
  const std::vector<double> start{0.0, 0.0, 0.0};
  IkOptions plain = with_method(IkMethod::pseudo_inverse, 400);
  IkOptions pulled = plain;
  pulled.preferred = preferred;
  std::vector<double> without(3), with(3);
  ASSERT_EQ(solve_ik(m, ik, goals, start, without, plain).status, IkStatus::converged);
  ASSERT_EQ(solve_ik(m, ik, goals, start, with, pulled).status, IkStatus::converged);
  const auto distance = [&](const std::vector<double>& q) {
    double sum = 0;
    for (std::size_t k = 0; k < 3; ++k) sum += (q[k] - preferred[k]) * (q[k] - preferred[k]);
    return std::sqrt(sum);
  };
  EXPECT_LT(distance(with), distance(without) - 0.05);
}

TEST(IkSolver, InvalidInputFailsWithTheClampedSeed) {
  const Model m = planar_two_link();
  IkWorkspace ik(m);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> seed{5.0, -0.5};  // the shoulder beyond its +3 limit
  std::vector<double> out(2);
  IkGoal bad_effector = IkGoal::at_position(7, Eigen::Vector3d(0.3, 0, 0));
  IkGoal not_finite = IkGoal::at_position(0, Eigen::Vector3d(nan, 0, 0));
  IkGoal zero_weight = IkGoal::at_position(0, Eigen::Vector3d(0.3, 0, 0), 0.0);
  IkGoal zero_aim = IkGoal::aiming(0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0));
  for (const IkGoal& goal : {bad_effector, not_finite, zero_weight, zero_aim}) {
    const IkResult r = solve_ik(m, ik, Goals{goal}, seed, out);
    EXPECT_EQ(r.status, IkStatus::failed);
    EXPECT_EQ(out, (std::vector<double>{3.0, -0.5}));
  }
  const IkGoal good = IkGoal::at_position(0, Eigen::Vector3d(0.3, 0.1, 0));
  EXPECT_EQ(solve_ik(m, ik, Goals{good, good}, seed, out).status, IkStatus::failed) << "more goals than the workspace holds";
  EXPECT_EQ(solve_ik(m, ik, Goals{}, seed, out).status, IkStatus::failed) << "no goal";
  EXPECT_EQ(solve_ik(m, ik, Goals{good}, std::vector<double>{nan, 0.5}, out).status, IkStatus::failed);
  EXPECT_EQ(out, (std::vector<double>{0.0, 0.5}));
}

}  // namespace
}  // namespace avar::kinematics
