#include "avar/kinematics/forward_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "test_models.hpp"

namespace avar::kinematics {
namespace {

/// Two revolute joints about z, links l1 and l2 along x, the hand at the end of the second.
Model planar_two_link(double l1, double l2) {
  ModelBuilder b;
  b.add_joint({"shoulder", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_joint({"elbow", JointType::revolute, "shoulder", test::translation(l1, 0, 0), Eigen::Vector3d::UnitZ(), -3, 3});
  b.add_effector({"hand", "elbow", test::translation(l2, 0, 0)});
  return b.build();
}

TEST(ForwardKinematics, PlanarTwoLinkMatchesTheClosedForm) {
  const std::uint64_t seed = 20261124;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const double l1 = 0.3, l2 = 0.2;
  const Model m = planar_two_link(l1, l2);
  Workspace ws(m);
  for (int sample = 0; sample < 200; ++sample) {
    const std::vector<double> q = test::random_configuration(m, rng);
    ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
    const Eigen::Isometry3d hand = effector_pose(m, ws, 0);
    EXPECT_NEAR(hand.translation().x(), l1 * std::cos(q[0]) + l2 * std::cos(q[0] + q[1]), 1e-14);
    EXPECT_NEAR(hand.translation().y(), l1 * std::sin(q[0]) + l2 * std::sin(q[0] + q[1]), 1e-14);
    EXPECT_NEAR(hand.translation().z(), 0, 1e-14);
    EXPECT_TRUE(hand.linear().isApprox(Eigen::AngleAxisd(q[0] + q[1], Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-14));
    EXPECT_TRUE(ws.joint_pose(1).translation().isApprox(Eigen::Vector3d(l1 * std::cos(q[0]), l1 * std::sin(q[0]), 0), 1e-14));
  }
}

TEST(ForwardKinematics, APrismaticJointTranslatesAlongItsAxisInItsOwnFrame) {
  ModelBuilder b;
  Eigen::Isometry3d turned(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  turned.translation() = Eigen::Vector3d(1, 0, 0);
  b.add_joint({"rail", JointType::prismatic, "", turned, Eigen::Vector3d(2, 0, 0), 0, 1});  // axis normalised to x
  b.add_effector({"carriage", "rail", Eigen::Isometry3d::Identity()});
  const Model m = b.build();
  Workspace ws(m);
  const std::vector<double> q{0.25};
  ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
  // The joint frame's x is the world's y.
  EXPECT_TRUE(effector_pose(m, ws, 0).translation().isApprox(Eigen::Vector3d(1, 0.25, 0), 1e-15));
  EXPECT_TRUE(effector_pose(m, ws, 0).linear().isApprox(turned.linear()));
}

TEST(ForwardKinematics, AtZeroEveryJointSitsAtItsComposedOrigins) {
  const Model m = test::branched_figure();
  Workspace ws(m);
  const std::vector<double> zero(m.dof(), 0.0);
  ASSERT_EQ(forward_kinematics(m, zero, ws), Status::ok);
  for (std::size_t i = 0; i < m.joint_count(); ++i) {
    Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
    for (std::size_t j = i; j != Joint::kNoParent; j = m.joint(j).parent) expected = m.joint(j).origin * expected;
    EXPECT_TRUE(ws.joint_pose(i).isApprox(expected, 1e-14)) << m.joint(i).name;
  }
}

TEST(ForwardKinematics, JointsOnOtherBranchesDoNotMoveAnEffector) {
  const std::uint64_t seed = 7;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const Model m = test::branched_figure();
  const std::size_t head = *m.find_effector("head");
  Workspace ws(m);
  for (int sample = 0; sample < 50; ++sample) {
    std::vector<double> q = test::random_configuration(m, rng);
    ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
    const Eigen::Isometry3d before = effector_pose(m, ws, head);
    for (const char* arm_joint : {"shoulder", "forearm", "elbow"}) {
      const std::size_t k = m.joint(*m.find_joint(arm_joint)).q_index;
      q[k] = test::uniform(rng, m.lower_limits()[k], m.upper_limits()[k]);
    }
    ASSERT_EQ(forward_kinematics(m, q, ws), Status::ok);
    EXPECT_TRUE(effector_pose(m, ws, head).isApprox(before, 0));
  }
}

TEST(ForwardKinematics, PosesStayRigid) {
  const std::uint64_t seed = 99;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int tree = 0; tree < 20; ++tree) {
    const Model m = test::random_tree(rng, 12);
    Workspace ws(m);
    ASSERT_EQ(forward_kinematics(m, test::random_configuration(m, rng), ws), Status::ok);
    for (std::size_t e = 0; e < m.effector_count(); ++e) {
      const Eigen::Matrix3d r = effector_pose(m, ws, e).linear();
      EXPECT_TRUE((r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
      EXPECT_NEAR(r.determinant(), 1, 1e-12);
    }
  }
}

TEST(ForwardKinematics, RefusesANonFiniteJointValueAndKeepsTheLastPoses) {
  const Model m = planar_two_link(0.3, 0.2);
  Workspace ws(m);
  ASSERT_EQ(forward_kinematics(m, std::vector<double>{0.1, 0.2}, ws), Status::ok);
  const Eigen::Isometry3d before = effector_pose(m, ws, 0);
  EXPECT_EQ(forward_kinematics(m, std::vector<double>{0.5, std::numeric_limits<double>::quiet_NaN()}, ws), Status::not_finite);
  EXPECT_EQ(forward_kinematics(m, std::vector<double>{std::numeric_limits<double>::infinity(), 0}, ws), Status::not_finite);
  EXPECT_TRUE(effector_pose(m, ws, 0).isApprox(before, 0));
}

}  // namespace
}  // namespace avar::kinematics
