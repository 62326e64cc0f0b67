#include "avar/kinematics/jacobian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "avar/kinematics/denavit_hartenberg.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// Compares the geometric Jacobian of every effector with central differences of its pose, at
/// `configurations` random configurations: linear part from the origin's motion, angular part
/// from the rotation between the two neighbouring frames.
void expect_jacobian_matches_finite_differences(const Model& m, std::mt19937_64& rng, int configurations) {
  Workspace ws(m);
  Jacobian J(6, static_cast<Eigen::Index>(m.dof()));
  const double h = 1e-6;
  for (int sample = 0; sample < configurations; ++sample) {
    const std::vector<double> q = test::random_configuration(m, rng);
    for (std::size_t e = 0; e < m.effector_count(); ++e) {
      SCOPED_TRACE("effector " + m.effector(e).name + ", configuration " + std::to_string(sample));
      ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
      geometric_jacobian(m, ws, e, J);
      for (std::size_t k = 0; k < m.dof(); ++k) {
        std::vector<double> plus = q, minus = q;
        plus[k] += h;
        minus[k] -= h;
        ASSERT_EQ(forward_kinematics(m, plus, ws), Status::ok);
        const Eigen::Isometry3d tp = effector_pose(m, ws, e);
        ASSERT_EQ(forward_kinematics(m, minus, ws), Status::ok);
        const Eigen::Isometry3d tm = effector_pose(m, ws, e);
        const Eigen::Vector3d v = (tp.translation() - tm.translation()) / (2 * h);
        const Eigen::AngleAxisd turn(tp.linear() * tm.linear().transpose());
        const Eigen::Vector3d w = turn.axis() * turn.angle() / (2 * h);
        const auto column = static_cast<Eigen::Index>(k);
        EXPECT_LT((J.block<3, 1>(0, column) - v).norm(), 1e-7) << "linear, column " << k;
        EXPECT_LT((J.block<3, 1>(3, column) - w).norm(), 1e-7) << "angular, column " << k;
      }
    }
  }
}

TEST(Jacobian, PlanarTwoLinkMatchesTheClosedForm) {
  const double l1 = 0.3, l2 = 0.2;
  const std::vector<DhRow> rows{{l1, 0, 0, 0, -3, 3, {}}, {l2, 0, 0, 0, -3, 3, {}}};
  const Model m = chain_from_standard_dh(rows);
  Workspace ws(m);
  const std::vector<double> q{0.4, -1.1};
  ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
  Jacobian J(6, 2);
  geometric_jacobian(m, ws, 0, J);
  const double s1 = std::sin(q[0]), c1 = std::cos(q[0]), s12 = std::sin(q[0] + q[1]), c12 = std::cos(q[0] + q[1]);
  Jacobian expected(6, 2);
  expected << -l1 * s1 - l2 * s12, -l2 * s12,  //
      l1 * c1 + l2 * c12, l2 * c12,            //
      0, 0,                                    //
      0, 0,                                    //
      0, 0,                                    //
      1, 1;
  EXPECT_TRUE(J.isApprox(expected, 1e-14)) << J;
}

using JacobianOfBenchChains = test::BenchChains;

TEST_F(JacobianOfBenchChains, MatchesFiniteDifferencesInBothDhConventions) {
  const std::uint64_t seed = 515;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (const DhChain& chain : chains) {
    SCOPED_TRACE(chain.name + ", standard DH");
    expect_jacobian_matches_finite_differences(chain_from_standard_dh(chain.rows), rng, 50);
    const test::ModifiedDh modified = test::modified_from_standard(chain.rows);
    SCOPED_TRACE(chain.name + ", modified DH");
    expect_jacobian_matches_finite_differences(chain_from_modified_dh(modified.rows, modified.tool), rng, 50);
  }
}

TEST(Jacobian, MatchesFiniteDifferencesOnABranchedFigureWithPrismaticJoints) {
  const std::uint64_t seed = 516;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  expect_jacobian_matches_finite_differences(test::branched_figure(), rng, 100);
}

TEST(Jacobian, MatchesFiniteDifferencesOnRandomTrees) {
  const std::uint64_t seed = 517;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int tree = 0; tree < 30; ++tree) {
    SCOPED_TRACE("tree " + std::to_string(tree));
    expect_jacobian_matches_finite_differences(test::random_tree(rng, 10), rng, 3);
  }
}

/// Whether joint `a` is `b` or one of its ancestors.
bool on_path(const Model& m, std::size_t a, std::size_t b) {
  for (std::size_t j = b; j != Joint::kNoParent; j = m.joint(j).parent)
    if (j == a) return true;
  return false;
}

TEST(Jacobian, ColumnsOfJointsOffTheEffectorsPathAreZero) {
  const std::uint64_t seed = 518;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int tree = 0; tree < 30; ++tree) {
    const Model m = tree == 0 ? test::branched_figure() : test::random_tree(rng, 10);
    Workspace ws(m);
    Jacobian J = Jacobian::Constant(6, static_cast<Eigen::Index>(m.dof()), 7.0);  // stale contents are overwritten
    ASSERT_EQ(forward_kinematics(m, test::random_configuration(m, rng), ws), Status::ok);
    for (std::size_t e = 0; e < m.effector_count(); ++e) {
      geometric_jacobian(m, ws, e, J);
      for (std::size_t j = 0; j < m.joint_count(); ++j) {
        if (!m.joint(j).movable()) continue;
        const auto column = static_cast<Eigen::Index>(m.joint(j).q_index);
        if (on_path(m, j, m.effector(e).joint))
          EXPECT_GT(J.col(column).norm(), 0) << "tree " << tree << ", effector " << e << ", joint " << j;
        else
          EXPECT_TRUE(J.col(column).isZero(0)) << "tree " << tree << ", effector " << e << ", joint " << j;
      }
    }
  }
}

TEST(Jacobian, WritesIntoABlockOfALargerMatrix) {
  const Model m = test::branched_figure();
  Workspace ws(m);
  ASSERT_EQ(forward_kinematics(m, std::vector<double>(m.dof(), 0.1), ws), Status::ok);
  const auto dof = static_cast<Eigen::Index>(m.dof());
  Jacobian alone(6, dof);
  geometric_jacobian(m, ws, 0, alone);
  // Two effectors stacked, as a solver tracking both would hold them.
  Eigen::MatrixXd stacked = Eigen::MatrixXd::Zero(6, 2 * dof);
  geometric_jacobian(m, ws, 0, stacked.leftCols(dof));
  geometric_jacobian(m, ws, 1, stacked.rightCols(dof));
  EXPECT_EQ(stacked.leftCols(dof), alone);
  EXPECT_FALSE(stacked.rightCols(dof).isZero());
}

}  // namespace
}  // namespace avar::kinematics
