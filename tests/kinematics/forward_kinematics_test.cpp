#include "avar/kinematics/forward_kinematics.hpp"

#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <fstream>
#include <random>
#include <unistd.h>

#include "avar/kinematics/denavit_hartenberg.hpp"


namespace avar::kinematics {
namespace {

const std::string kChains = AVAR_SOURCE_DIR "/../shared/bench/ik-chains.txt";

Model planar_two_link(double l1, double l2) {
  const std::vector<DhRow> rows{{l1, 0, 0, 0, -3, 3}, {l2, 0, 0, 0, -3, 3}};
  return chain_from_standard_dh(rows);
}

/// A branched tree with a prismatic joint and a fixed joint: a torso that slides, a neck, and
/// two arms.
Model tree() {
  ModelBuilder b;
  Joint slide{"slide", JointType::prismatic, -1, Eigen::Isometry3d::Identity(), Eigen::Vector3d(0, 0, 1), -0.2, 0.2, -1, {}};
  const auto torso = static_cast<int>(b.add_joint(slide));
  Joint neck{"neck", JointType::revolute, torso, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.4)), Eigen::Vector3d(0, 0, 1), -1, 1, -1, {}};
  b.add_joint(neck);
  Joint shoulder{"shoulder", JointType::revolute, torso, Eigen::Isometry3d(Eigen::Translation3d(0.2, 0, 0.3)), Eigen::Vector3d(1, 1, 0), -2, 2, -1, {}};
  const auto s = static_cast<int>(b.add_joint(shoulder));
  Joint mount{"mount", JointType::fixed, s, Eigen::Isometry3d(Eigen::Translation3d(0, 0.1, 0)), Eigen::Vector3d::UnitZ(), 0, 0, -1, {}};
  const auto m = static_cast<int>(b.add_joint(mount));
  Joint elbow{"elbow", JointType::revolute, m, Eigen::Isometry3d(Eigen::Translation3d(0.25, 0, 0)), Eigen::Vector3d(0, 1, 0), -2, 2, -1, {}};
  const auto e = b.add_joint(elbow);
  b.add_effector({"hand", e, Eigen::Isometry3d(Eigen::Translation3d(0.2, 0, 0.05))});
  b.add_effector({"head", 1, Eigen::Isometry3d(Eigen::Translation3d(0.1, 0, 0.1))});
  return b.build();
}

TEST(ForwardKinematics, PlanarTwoLinkMatchesTheClosedForm) {
  const Model m = planar_two_link(0.3, 0.2);
  Workspace ws(m);
  const std::vector<double> q{0.4, -1.1};
  forward_kinematics(m, q, ws);
  const Eigen::Vector3d p = effector_pose(m, ws, 0).translation();
  EXPECT_NEAR(p.x(), 0.3 * std::cos(0.4) + 0.2 * std::cos(0.4 - 1.1), 1e-12);
  EXPECT_NEAR(p.y(), 0.3 * std::sin(0.4) + 0.2 * std::sin(0.4 - 1.1), 1e-12);
  EXPECT_NEAR(p.z(), 0, 1e-12);
}

TEST(ForwardKinematics, ModifiedAndStandardDhDescribeTheSameArm) {
  const Model standard = planar_two_link(0.3, 0.2);
  const std::vector<DhRow> modified_rows{{0, 0, 0, 0, -3, 3}, {0.3, 0, 0, 0, -3, 3}};
  const Model modified_chain = chain_from_modified_dh(modified_rows);
  Workspace ws_s(standard), ws_m(modified_chain);
  const std::vector<double> q{0.7, 0.5};
  forward_kinematics(standard, q, ws_s);
  forward_kinematics(modified_chain, q, ws_m);
  // The modified chain's last frame sits at the elbow; the hand is 0.2 m along its x axis.
  const Eigen::Vector3d hand_m = (effector_pose(modified_chain, ws_m, 0) * Eigen::Translation3d(0.2, 0, 0)).translation();
  EXPECT_TRUE(hand_m.isApprox(effector_pose(standard, ws_s, 0).translation(), 1e-12));
}

TEST(ForwardKinematics, Ur5HomePoseFromTheBenchmarkChains) {
  if (!std::filesystem::exists(kChains)) GTEST_SKIP() << "the shared reference chains are missing: " << kChains;
  const auto chains = read_dh_chains(kChains);
  ASSERT_GE(chains.size(), 2u);
  EXPECT_EQ(chains[0].name, "ur5");
  const Model ur5 = chain_from_standard_dh(chains[0].rows);
  ASSERT_EQ(ur5.dof(), 6u);
  Workspace ws(ur5);
  const std::vector<double> zero(6, 0.0);
  forward_kinematics(ur5, zero, ws);
  // UR5 at all-zero joints: x = a2 + a3, y = -(d4 + d6), z = d1 - d5.
  const Eigen::Vector3d p = effector_pose(ur5, ws, 0).translation();
  EXPECT_NEAR(p.x(), -0.425 - 0.39225, 1e-9);
  EXPECT_NEAR(p.y(), -(0.10915 + 0.0823), 1e-9);
  EXPECT_NEAR(p.z(), 0.089159 - 0.09465, 1e-9);
}

/// Central differences of the effector pose against the geometric Jacobian.
void expect_jacobian_matches_finite_differences(const Model& m, std::size_t effector, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Workspace ws(m);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, static_cast<Eigen::Index>(m.dof()));
  std::vector<double> q(m.dof());
  for (const Joint& j : m.joints())
    if (j.q_index >= 0) q[static_cast<std::size_t>(j.q_index)] = j.lower + (j.upper - j.lower) * u(rng);
  forward_kinematics(m, q, ws);
  geometric_jacobian(m, ws, effector, J);
  const double h = 1e-6;
  for (std::size_t k = 0; k < m.dof(); ++k) {
    std::vector<double> qp = q, qm = q;
    qp[k] += h;
    qm[k] -= h;
    forward_kinematics(m, qp, ws);
    const Eigen::Isometry3d Tp = effector_pose(m, ws, effector);
    forward_kinematics(m, qm, ws);
    const Eigen::Isometry3d Tm = effector_pose(m, ws, effector);
    const Eigen::Vector3d v = (Tp.translation() - Tm.translation()) / (2 * h);
    const Eigen::AngleAxisd dR(Tp.linear() * Tm.linear().transpose());
    const Eigen::Vector3d w = dR.axis() * dR.angle() / (2 * h);
    const auto col = static_cast<Eigen::Index>(k);
    EXPECT_LT((J.block<3, 1>(0, col) - v).norm(), 1e-6) << "linear column " << k;
    EXPECT_LT((J.block<3, 1>(3, col) - w).norm(), 1e-6) << "angular column " << k;
  }
}

TEST(Jacobian, MatchesFiniteDifferencesOverRandomConfigurations) {
  const unsigned seed = 515;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  const Model t = tree();
  for (int i = 0; i < 50; ++i) {
    expect_jacobian_matches_finite_differences(t, 0, rng);
    expect_jacobian_matches_finite_differences(t, 1, rng);
  }
  if (!std::filesystem::exists(kChains)) GTEST_SKIP() << "the shared reference chains are missing: " << kChains;
  for (const auto& chain : read_dh_chains(kChains)) {
    SCOPED_TRACE(chain.name);
    const Model m = chain_from_standard_dh(chain.rows);
    for (int i = 0; i < 50; ++i) expect_jacobian_matches_finite_differences(m, 0, rng);
  }
}

TEST(Jacobian, JointsOffTheEffectorsPathHaveZeroColumns) {
  const Model t = tree();
  Workspace ws(t);
  std::vector<double> q(t.dof(), 0.3);
  forward_kinematics(t, q, ws);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, static_cast<Eigen::Index>(t.dof()));
  geometric_jacobian(t, ws, 1, J);  // the head: slide and neck only
  EXPECT_GT(J.col(0).norm(), 0);
  EXPECT_GT(J.col(1).norm(), 0);
  EXPECT_EQ(J.col(2).norm(), 0);
  EXPECT_EQ(J.col(3).norm(), 0);
}

TEST(ForwardKinematics, NoAllocationAfterTheWorkspaceExists) {
  const Model t = tree();
  Workspace ws(t);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, static_cast<Eigen::Index>(t.dof()));
  std::vector<double> q(t.dof(), 0.1);
  const long before = testing::allocations.load();
  for (int i = 0; i < 1000; ++i) {
    q[0] = 0.0001 * i;
    forward_kinematics(t, q, ws);
    geometric_jacobian(t, ws, 0, J);
  }
  EXPECT_EQ(testing::allocations.load() - before, 0);
}

TEST(ModelBuilder, RejectsBadJointsWithTheirLocation) {
  auto message = [](Joint j) -> std::string {
    ModelBuilder b;
    b.add_joint(j);
    try {
      b.build();
      return "";
    } catch (const InputError& e) {
      return e.what();
    }
  };
  Joint j{"pan", JointType::revolute, -1, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(), -1, 1, -1, {"rig.yaml", 12, 5}};
  EXPECT_EQ(message(j), "rig.yaml:12:5: joint 'pan': expected a non-zero axis, found (0, 0, 0)");
  j.axis = Eigen::Vector3d::UnitZ();
  j.lower = 2;
  EXPECT_EQ(message(j), "rig.yaml:12:5: joint 'pan': expected finite limits with lower <= upper");
  j.lower = -1;
  j.parent = 0;
  EXPECT_EQ(message(j), "rig.yaml:12:5: joint 'pan': its parent must be an earlier joint or the base (joints are listed parents first, so no cycle can form)");
  ModelBuilder dup;
  j.parent = -1;
  dup.add_joint(j);
  dup.add_joint(j);
  EXPECT_THROW(dup.build(), InputError);
}

TEST(DhChainReader, RejectsMalformedFilesWithTheLine) {
  const std::string path = ::testing::TempDir() + "avar-dh-" + std::to_string(::getpid()) + ".txt";
  std::ofstream(path) << "# test\nchain arm 2\n0 0 0 0 -1 1\n0 0 zero 0 -1 1\n";
  try {
    read_dh_chains(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":4:1: expected six numbers: a alpha d theta lower upper");
  }
}

}  // namespace
}  // namespace avar::kinematics
