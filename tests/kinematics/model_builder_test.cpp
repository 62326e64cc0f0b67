#include "avar/kinematics/model_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "test_models.hpp"

namespace avar::kinematics {
namespace {

const SourceLocation kAt{"rig.yaml", 12, 5};

/// The message of the InputError that adding `spec` after a joint "torso" throws; empty when
/// nothing is thrown.
std::string joint_error(const JointSpec& spec) {
  ModelBuilder b;
  b.add_joint({"torso", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1}, {"rig.yaml", 3, 5});
  try {
    b.add_joint(spec, kAt);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, kAt.line);
    return e.what();
  }
  return "";
}

JointSpec good_joint() {
  return {"pan", JointType::revolute, "torso", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1};
}

TEST(ModelBuilder, BuildsTheTreeInDeclarationOrder) {
  const Model m = test::branched_figure();
  ASSERT_EQ(m.joint_count(), 6u);
  EXPECT_EQ(m.dof(), 5u);  // the mount is fixed
  EXPECT_TRUE(m.joint(0).on_base());
  EXPECT_EQ(m.joint(2).parent, 0u);
  EXPECT_EQ(m.joint(4).parent, 3u);
  EXPECT_FALSE(m.joint(3).movable());
  EXPECT_EQ(m.joint(4).q_index, 3u);  // the fixed mount takes no entry of q
  EXPECT_EQ(m.joint(5).q_index, 4u);
  EXPECT_NEAR(m.joint(2).axis.norm(), 1, 1e-15);
  EXPECT_TRUE(m.joint(2).axis.isApprox(Eigen::Vector3d(1, 1, 0).normalized()));
  EXPECT_EQ(m.lower_limits()[3], 0);
  EXPECT_EQ(m.upper_limits()[3], 0.15);
  EXPECT_EQ(m.find_joint("elbow"), 5u);
  EXPECT_EQ(m.find_joint("knee"), std::nullopt);
  EXPECT_EQ(m.find_effector("head"), 1u);
  EXPECT_EQ(m.effector(0).joint, 5u);
}

TEST(ModelBuilder, KeepsTheSourceLocationOfEachJoint) {
  ModelBuilder b;
  b.add_joint({"pan", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1}, kAt);
  const Model m = b.build();
  EXPECT_EQ(m.joint(0).where.file, "rig.yaml");
  EXPECT_EQ(m.joint(0).where.line, 12);
  EXPECT_EQ(m.joint(0).where.column, 5);
}

TEST(ModelBuilder, AcceptsAGoodJoint) { EXPECT_EQ(joint_error(good_joint()), ""); }

TEST(ModelBuilder, RejectsAnEmptyName) {
  JointSpec j = good_joint();
  j.name = "";
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: expected a joint name, found an empty one");
}

TEST(ModelBuilder, RejectsADuplicateName) {
  JointSpec j = good_joint();
  j.name = "torso";
  EXPECT_EQ(joint_error(j),
            "rig.yaml:12:5: joint 'torso': the name is taken by joint 0 (declared at rig.yaml:3:5); expected unique joint names");
}

TEST(ModelBuilder, RejectsAnUnknownParent) {
  JointSpec j = good_joint();
  j.parent = "neck";
  EXPECT_EQ(joint_error(j),
            "rig.yaml:12:5: joint 'pan': parent 'neck' is not a joint declared before it; expected the name of an earlier "
            "joint (parents come before their children) or no parent for a joint on the base");
}

TEST(ModelBuilder, RejectsItselfAsParentSoNoCycleCanForm) {
  JointSpec j = good_joint();
  j.parent = "pan";
  EXPECT_NE(joint_error(j).find("parent 'pan' is not a joint declared before it"), std::string::npos);
}

TEST(ModelBuilder, RejectsAZeroAxis) {
  JointSpec j = good_joint();
  j.axis = Eigen::Vector3d::Zero();
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': expected a non-zero finite axis, found (0, 0, 0)");
}

TEST(ModelBuilder, RejectsANonFiniteAxis) {
  JointSpec j = good_joint();
  j.type = JointType::prismatic;
  j.axis = Eigen::Vector3d(1, std::numeric_limits<double>::quiet_NaN(), 0);
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': expected a non-zero finite axis, found (1, nan, 0)");
  j.axis = Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0);
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': expected a non-zero finite axis, found (inf, 0, 0)");
}

TEST(ModelBuilder, IgnoresTheAxisAndLimitsOfAFixedJoint) {
  JointSpec j = good_joint();
  j.type = JointType::fixed;
  j.axis = Eigen::Vector3d::Zero();
  j.lower = 1;
  j.upper = -1;
  EXPECT_EQ(joint_error(j), "");
}

TEST(ModelBuilder, RejectsLowerAboveUpper) {
  JointSpec j = good_joint();
  j.lower = 2;
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': expected finite limits with lower <= upper, found lower 2, upper 1");
}

TEST(ModelBuilder, RejectsNonFiniteLimits) {
  JointSpec j = good_joint();
  j.upper = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': expected finite limits with lower <= upper, found lower -1, upper nan");
}

TEST(ModelBuilder, RejectsANonFiniteOrigin) {
  JointSpec j = good_joint();
  j.origin.translation().x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(joint_error(j), "rig.yaml:12:5: joint 'pan': the origin has non-finite entries; expected a finite rigid transform");
}

TEST(ModelBuilder, RejectsAnOriginThatIsNotRigid) {
  JointSpec j = good_joint();
  j.origin.linear() = Eigen::Vector3d(1, 1, 2).asDiagonal();
  const std::string expected =
      "rig.yaml:12:5: joint 'pan': the origin is not rigid; expected a rotation (orthonormal columns, determinant +1) and "
      "a translation";
  EXPECT_EQ(joint_error(j), expected);
  j.origin.linear() = Eigen::Vector3d(1, 1, -1).asDiagonal();  // a reflection
  EXPECT_EQ(joint_error(j), expected);
}

TEST(ModelBuilder, LeavesTheModelUnchangedWhenAJointIsRejected) {
  ModelBuilder b;
  b.add_joint({"pan", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1});
  EXPECT_THROW(b.add_joint({"tilt", JointType::revolute, "pan", Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(), -1, 1}),
               InputError);
  EXPECT_EQ(b.build().joint_count(), 1u);
  EXPECT_EQ(b.build().dof(), 1u);
}

/// The message of the InputError that adding `spec` after a joint "neck" and an effector
/// "head" throws; empty when nothing is thrown.
std::string effector_error(const EffectorSpec& spec) {
  ModelBuilder b;
  b.add_joint({"neck", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1});
  b.add_effector({"head", "neck", Eigen::Isometry3d::Identity()}, {"rig.yaml", 7, 3});
  try {
    b.add_effector(spec, kAt);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelBuilder, RejectsBadEffectors) {
  EXPECT_EQ(effector_error({"eye", "neck", test::translation(0.1, 0, 0)}), "");
  EXPECT_EQ(effector_error({"", "neck", Eigen::Isometry3d::Identity()}), "rig.yaml:12:5: expected an effector name, found an empty one");
  EXPECT_EQ(effector_error({"head", "neck", Eigen::Isometry3d::Identity()}),
            "rig.yaml:12:5: effector 'head': the name is taken by effector 0 (declared at rig.yaml:7:3); expected unique "
            "effector names");
  EXPECT_EQ(effector_error({"hand", "wrist", Eigen::Isometry3d::Identity()}),
            "rig.yaml:12:5: effector 'hand': joint 'wrist' does not exist; expected the name of a joint added before the "
            "effector");
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2;
  EXPECT_EQ(effector_error({"eye", "neck", scaled}),
            "rig.yaml:12:5: effector 'eye': the tool transform is not rigid; expected a rotation (orthonormal columns, "
            "determinant +1) and a translation");
}

TEST(ModelBuilder, WithoutALocationTheMessageSaysInput) {
  ModelBuilder b;
  try {
    b.add_joint({"pan", JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(), -1, 1});
    FAIL() << "a zero axis was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<input>: joint 'pan': expected a non-zero finite axis, found (0, 0, 0)");
  }
}

}  // namespace
}  // namespace avar::kinematics
