// The kinematics hot path allocates nothing once the Model, Workspace and Jacobian exist.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
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

}  // namespace
}  // namespace avar::kinematics
