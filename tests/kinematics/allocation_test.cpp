// The kinematics hot path allocates nothing once the Model, Workspace and Jacobian exist.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/ik_solver.hpp"
#include "avar/kinematics/jacobian.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

TEST(KinematicsAllocation, ForwardKinematicsEffectorPosesAndJacobiansAllocateNothing) {
  const std::uint64_t seed = 3;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const Model m = test::random_tree(rng, 16);
  Workspace ws(m);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, static_cast<Eigen::Index>(m.dof()));
  std::vector<std::vector<double>> configurations;
  for (int i = 0; i < 100; ++i) configurations.push_back(test::random_configuration(m, rng));
  double checksum = 0;

  const long before = testing::allocations.load();
  for (const std::vector<double>& q : configurations) {
    if (forward_kinematics(m, q, ws) != Status::ok) checksum = -1;
    for (std::size_t e = 0; e < m.effector_count(); ++e) {
      checksum += effector_pose(m, ws, e).translation().sum();
      geometric_jacobian(m, ws, e, J);
      checksum += J.sum();
    }
  }
  const long during = testing::allocations.load() - before;

  EXPECT_EQ(during, 0);
  EXPECT_TRUE(std::isfinite(checksum));
}

TEST(KinematicsAllocation, EveryIkMethodSolvesWithoutAllocating) {
  const std::uint64_t seed = 4;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const Model m = test::random_tree(rng, 12);
  IkWorkspace ik(m, 3);
  std::vector<std::vector<IkGoal>> goal_sets;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Isometry3d target = test::random_rigid(rng, 0.5);
    goal_sets.push_back({IkGoal::at_pose(m.effector_count() - 1, target),
                         IkGoal::at_position(m.effector_count() / 2, target.translation()),
                         IkGoal::aiming(0, Eigen::Vector3d::UnitX(), target.translation())});
    goal_sets.push_back({IkGoal::at_orientation(1, Eigen::Quaterniond(target.linear()))});
  }
  std::vector<double> q(m.dof(), 0.0);
  const std::vector<double> preferred(m.dof(), 0.1);
  std::vector<IkOptions> option_sets;
  for (const IkMethod method : {IkMethod::damped_least_squares, IkMethod::pseudo_inverse, IkMethod::jacobian_transpose,
                                IkMethod::cyclic_coordinate_descent}) {
    IkOptions options = cold_start_ik_options();
    options.method = method;
    options.restarts = 2;
    options.preferred = preferred;
    option_sets.push_back(options);
  }
  int iterations = 0;

  const long before = testing::allocations.load();
  for (const IkOptions& options : option_sets)
    for (const std::vector<IkGoal>& goals : goal_sets) iterations += solve_ik(m, ik, goals, q, q, options).iterations;
  const long during = testing::allocations.load() - before;

  EXPECT_EQ(during, 0);
  EXPECT_GT(iterations, 0);
}

}  // namespace
}  // namespace avar::kinematics
