#include "avar/kinematics/analytic_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "avar/kinematics/forward_kinematics.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

Eigen::Vector2d reach(const TwoLinkArm& arm, const TwoLinkAngles& a) {
  return {arm.upper_length * std::cos(a.shoulder) + arm.lower_length * std::cos(a.shoulder + a.elbow),
          arm.upper_length * std::sin(a.shoulder) + arm.lower_length * std::sin(a.shoulder + a.elbow)};
}

const TwoLinkArm kArm{0.3, 0.2, {-3, 3}, {-3, 3}};

TEST(TwoLinkReach, RandomReachableTargetsAreMetByBothBends) {
  const std::uint64_t seed = 41;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int sample = 0; sample < 500; ++sample) {
    const TwoLinkAngles truth{test::uniform(rng, -3, 3), test::uniform(rng, -2.9, 2.9)};
    const Eigen::Vector2d target = reach(kArm, truth);
    for (const ElbowBend bend : {ElbowBend::up, ElbowBend::down}) {
      TwoLinkAngles out;
      const IkResult r = solve_two_link(kArm, target, bend, out);
      if (r.status != IkStatus::converged) {
        // Only a shoulder limit can stop it: the mirror solution may need the shoulder past +-3.
        EXPECT_EQ(r.status, IkStatus::degraded);
        EXPECT_TRUE(out.shoulder == 3 || out.shoulder == -3) << "sample " << sample;
        continue;
      }
      EXPECT_LT((reach(kArm, out) - target).norm(), 1e-12) << "sample " << sample;
      EXPECT_TRUE(bend == ElbowBend::up ? out.elbow <= 0 : out.elbow >= 0) << "sample " << sample;
    }
  }
}

TEST(TwoLinkReach, ElbowUpPutsTheElbowLeftOfTheReachLine) {
  TwoLinkAngles out;
  ASSERT_EQ(solve_two_link(kArm, Eigen::Vector2d(0.4, 0), ElbowBend::up, out).status, IkStatus::converged);
  EXPECT_GT(kArm.upper_length * std::sin(out.shoulder), 0);
  ASSERT_EQ(solve_two_link(kArm, Eigen::Vector2d(0.4, 0), ElbowBend::down, out).status, IkStatus::converged);
  EXPECT_LT(kArm.upper_length * std::sin(out.shoulder), 0);
}

TEST(TwoLinkReach, OutOfReachGivesTheClosestPointAndDegraded) {
  TwoLinkAngles out;
  const Eigen::Vector2d far(0.6, 0.3);
  IkResult r = solve_two_link(kArm, far, ElbowBend::up, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  EXPECT_LT((reach(kArm, out) - far.normalized() * 0.5).norm(), 1e-12);
  EXPECT_NEAR(r.position_error, far.norm() - 0.5, 1e-12);

  const Eigen::Vector2d near(0.02, 0.05);  // inside the 0.1 m hole the folded arm cannot reach
  const TwoLinkArm folding{0.3, 0.2, {-3, 3}, {-3.2, 3.2}};
  r = solve_two_link(folding, near, ElbowBend::down, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  EXPECT_NEAR(r.position_error, 0.1 - near.norm(), 1e-12);
}

TEST(TwoLinkReach, ElbowLimitIsRespectedAndReported) {
  const TwoLinkArm stiff{0.3, 0.2, {-3, 3}, {0.2, 1.0}};
  TwoLinkAngles out;
  const Eigen::Vector2d target(0.15, 0);  // needs the elbow bent about 2.6 rad
  const IkResult r = solve_two_link(stiff, target, ElbowBend::down, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  EXPECT_DOUBLE_EQ(out.elbow, 1.0);
  EXPECT_NEAR(r.position_error, (reach(stiff, out) - target).norm(), 1e-12);
}

TEST(TwoLinkReach, NonFiniteTargetFails) {
  TwoLinkAngles out;
  EXPECT_EQ(solve_two_link(kArm, Eigen::Vector2d(NAN, 0), ElbowBend::up, out).status, IkStatus::failed);
  EXPECT_EQ(solve_two_link({0, 0.2, {}, {}}, Eigen::Vector2d(0.1, 0), ElbowBend::up, out).status, IkStatus::failed);
}

/// The same gimbal as a joint tree: pan (z), tilt (y), roll (x), the effector on the roll joint.
Model gimbal_model(const PanTiltHead& head) {
  ModelBuilder b;
  b.add_joint({"pan", JointType::revolute, "", head.mount, Eigen::Vector3d::UnitZ(), head.pan.lower, head.pan.upper});
  b.add_joint({"tilt", JointType::revolute, "pan", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitY(), head.tilt.lower,
               head.tilt.upper});
  b.add_joint({"roll", JointType::revolute, "tilt", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), head.roll.lower,
               head.roll.upper});
  b.add_effector({"sight", "roll"});
  return b.build();
}

Eigen::Isometry3d sight_pose(const Model& m, const PanTiltRollAngles& a) {
  Workspace ws(m);
  const std::vector<double> q{a.pan, a.tilt, a.roll};
  EXPECT_EQ(forward_kinematics(m, q, ws), Status::ok);
  return effector_pose(m, ws, 0);
}

double miss_angle(const Eigen::Isometry3d& sight, const Eigen::Vector3d& target) {
  const Eigen::Vector3d axis = sight.linear() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d want = (target - sight.translation()).normalized();
  return std::atan2(axis.cross(want).norm(), axis.dot(want));
}

TEST(AimHead, PointsTheSightOfTheJointTreeAtRandomTargets) {
  const std::uint64_t seed = 42;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  PanTiltHead head{test::random_rigid(rng, 0.5), {-3.1, 3.1}, {-1.5, 1.5}, {-1, 1}};
  const Model m = gimbal_model(head);
  for (int sample = 0; sample < 300; ++sample) {
    // Targets the limits allow: drawn from angles within them, at a random distance.
    const PanTiltRollAngles truth{test::uniform(rng, -3.1, 3.1), test::uniform(rng, -1.5, 1.5), 0};
    const Eigen::Isometry3d s = sight_pose(m, truth);
    const Eigen::Vector3d target = s * Eigen::Vector3d(test::uniform(rng, 0.1, 3), 0, 0);
    PanTiltRollAngles out;
    const double roll = test::uniform(rng, -0.5, 0.5);
    const IkResult r = aim_head(head, target, out, roll);
    ASSERT_EQ(r.status, IkStatus::converged) << "sample " << sample;
    EXPECT_LT(miss_angle(sight_pose(m, out), target), 1e-9) << "sample " << sample;
    EXPECT_DOUBLE_EQ(out.roll, roll);
  }
}

TEST(AimHead, TargetBeyondThePanLimitGivesTheClosestSightAndDegraded) {
  const PanTiltHead head{Eigen::Isometry3d::Identity(), {-1, 1}, {-0.5, 0.5}, {0, 0}};
  const Model m = gimbal_model(head);
  PanTiltRollAngles out;
  const Eigen::Vector3d behind(-1, 0.2, 0);
  const IkResult r = aim_head(head, behind, out);
  EXPECT_EQ(r.status, IkStatus::degraded);
  EXPECT_DOUBLE_EQ(out.pan, 1.0);
  EXPECT_NEAR(r.orientation_error, miss_angle(sight_pose(m, out), behind), 1e-12);
  // No sight within the limits does better (a grid over the pan and tilt ranges).
  for (double pan = -1; pan <= 1; pan += 0.02)
    for (double tilt = -0.5; tilt <= 0.5; tilt += 0.02)
      EXPECT_GE(miss_angle(sight_pose(m, {pan, tilt, 0}), behind), r.orientation_error - 1e-12);

  const Eigen::Vector3d high(1, 0, 2);  // 63 degrees up, the tilt stops at 0.5 rad
  EXPECT_EQ(aim_head(head, high, out).status, IkStatus::degraded);
  EXPECT_DOUBLE_EQ(out.tilt, -0.5);
}

TEST(AimHead, TargetAtTheCentreFails) {
  PanTiltRollAngles out;
  EXPECT_EQ(aim_head(PanTiltHead{}, Eigen::Vector3d::Zero(), out).status, IkStatus::failed);
}

TEST(AimEyes, BothEyesConvergeOnANearTargetFromTheirOwnCentres) {
  const PanTiltHead left{test::translation(0.05, 0.03, 0.1), {-0.8, 0.8}, {-0.6, 0.6}, {0, 0}};
  const PanTiltHead right{test::translation(0.05, -0.03, 0.1), {-0.8, 0.8}, {-0.6, 0.6}, {0, 0}};
  Eigen::Isometry3d head_pose(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  head_pose.translation() = Eigen::Vector3d(0.2, -0.1, 1.2);
  const Eigen::Vector3d target = head_pose * Eigen::Vector3d(0.35, 0.0, 0.12);  // 30 cm ahead, between the eyes
  PanTiltRollAngles l, r;
  ASSERT_EQ(aim_eyes(left, right, head_pose, target, l, r).status, IkStatus::converged);
  EXPECT_LT(l.pan, 0) << "the left eye turns right, toward the middle";
  EXPECT_GT(r.pan, 0) << "the right eye turns left, toward the middle";
  PanTiltHead left_world = left, right_world = right;
  left_world.mount = head_pose * left.mount;
  right_world.mount = head_pose * right.mount;
  EXPECT_LT(miss_angle(sight_pose(gimbal_model(left_world), l), target), 1e-9);
  EXPECT_LT(miss_angle(sight_pose(gimbal_model(right_world), r), target), 1e-9);
}

}  // namespace
}  // namespace avar::kinematics
