#include "avar/kinematics/urdf_import.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "avar/kinematics/forward_kinematics.hpp"
#include "avar/kinematics/ik_solver.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

const std::string kFixtures = AVAR_SOURCE_DIR "/tests/kinematics/fixtures/";

Eigen::Isometry3d pose_of(const Model& m, const std::vector<double>& q, const std::string& effector) {
  Workspace ws(m);
  EXPECT_EQ(forward_kinematics(m, q, ws), Status::ok);
  return effector_pose(m, ws, *m.find_effector(effector));
}

TEST(UrdfImport, PanTiltHeadHasItsJointsLimitsLinesAndGeometry) {
  const Model m = model_from_urdf_file(kFixtures + "pan_tilt_head.urdf");
  ASSERT_EQ(m.joint_count(), 3u);
  ASSERT_EQ(m.dof(), 2u);
  EXPECT_EQ(m.joint(0).name, "pan");
  EXPECT_EQ(m.joint(1).name, "tilt");
  EXPECT_EQ(m.joint(2).type, JointType::fixed);
  EXPECT_EQ(m.joint(1).where.line, 15);
  EXPECT_EQ(m.joint(1).where.file, kFixtures + "pan_tilt_head.urdf");
  EXPECT_DOUBLE_EQ(m.lower_limits()[1], -0.6);
  EXPECT_DOUBLE_EQ(m.upper_limits()[1], 0.8);
  ASSERT_TRUE(m.find_effector("eye"));
  ASSERT_TRUE(m.find_effector("neck"));
  EXPECT_FALSE(m.find_effector("base")) << "the root link has no joint to hang from";

  const double pan = 0.4, tilt = -0.3;
  const Eigen::Vector3d expected = Eigen::Vector3d(0, 0, 0.35) + Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) *
                                                                     Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()) *
                                                                     Eigen::Vector3d(0.08, 0, 0.02);
  EXPECT_LT((pose_of(m, {pan, tilt}, "eye").translation() - expected).norm(), 1e-12);
}

TEST(UrdfImport, ThreeLinkArmMatchesTheSameArmBuiltByHand) {
  const Model m = model_from_urdf_file(kFixtures + "three_link_arm.urdf");
  ModelBuilder b;
  b.add_joint({"lift", JointType::prismatic, "", test::translation(0, 0, 0.1), Eigen::Vector3d::UnitZ(), 0, 0.2});
  // rpy = (roll, pitch, yaw) about fixed x, y, z: R = Rz(yaw) Ry(pitch) Rx(roll).
  Eigen::Isometry3d shoulder = test::translation(0, 0, 0.05);
  shoulder.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  b.add_joint({"shoulder", JointType::revolute, "lift", shoulder, Eigen::Vector3d::UnitZ(), -2, 2});
  b.add_joint({"elbow", JointType::revolute, "shoulder", test::translation(0.25, 0, 0), Eigen::Vector3d::UnitZ(), -2.5, 2.5});
  b.add_joint({"wrist", JointType::revolute, "elbow", test::translation(0.2, 0, 0), Eigen::Vector3d::UnitX(),
               -2 * std::numbers::pi, 2 * std::numbers::pi});
  Eigen::Isometry3d tool = test::translation(0.05, 0, 0);
  tool.rotate(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()));
  b.add_joint({"tool_mount", JointType::fixed, "wrist", tool, Eigen::Vector3d::Zero(), 0, 0});
  b.add_effector({"tool", "tool_mount"});
  const Model by_hand = b.build();

  ASSERT_EQ(m.dof(), 4u);
  EXPECT_DOUBLE_EQ(m.upper_limits()[3], 2 * std::numbers::pi) << "continuous joints get one turn either way";
  const std::uint64_t seed = 51;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int sample = 0; sample < 50; ++sample) {
    const std::vector<double> q = test::random_configuration(m, rng);
    const Eigen::Isometry3d a = pose_of(m, q, "tool"), h = pose_of(by_hand, q, "tool");
    EXPECT_TRUE(a.matrix().isApprox(h.matrix(), 1e-12)) << "sample " << sample;
  }
}

TEST(UrdfImport, ImportedHeadAimsWithTheNumericSolver) {
  const Model m = model_from_urdf_file(kFixtures + "pan_tilt_head.urdf");
  IkWorkspace ik(m);
  const std::vector<IkGoal> goals{IkGoal::aiming(*m.find_effector("eye"), Eigen::Vector3d::UnitX(), Eigen::Vector3d(1, 0.5, 0.2))};
  std::vector<double> q(2, 0.0);
  EXPECT_EQ(solve_ik(m, ik, goals, q, q).status, IkStatus::converged);
}

void expect_rejected(const std::string& fixture, int line, const std::string& found, const std::string& expected) {
  SCOPED_TRACE(fixture);
  try {
    model_from_urdf_file(kFixtures + fixture);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, kFixtures + fixture);
    EXPECT_EQ(e.where().line, line);
    EXPECT_NE(e.problem().find(found), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find(expected), std::string::npos) << e.what();
  }
}

TEST(UrdfImport, BadFixturesAreRejectedWithWhereAndWhat) {
  expect_rejected("bad_missing_limits.urdf", 10, "joint 'bc' (revolute) has no limits", "expected <limit lower=");
  expect_rejected("bad_zero_axis.urdf", 9, "joint 'ab' has axis (0, 0, 0)", "expected a non-zero");
  expect_rejected("bad_unknown_type.urdf", 10, "type 'floating'", "expected type=\"revolute\"");
  expect_rejected("bad_cycle.urdf", 6, "joint 'ab' closes a cycle", "expected a tree");
}

void expect_text_rejected(const std::string& body, int line, const std::string& found) {
  const std::string text = "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n" + body + "</robot>\n";
  try {
    model_from_urdf_text(text, "inline.urdf");
    FAIL() << "accepted: " << body;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "inline.urdf");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_NE(e.problem().find(found), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find("expected"), std::string::npos) << e.what();
  }
}

TEST(UrdfImport, OtherBadDescriptionsAreRejectedWithWhereAndWhat) {
  const std::string ab = "  <joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n";
  expect_text_rejected(ab + "  <joint name=\"k\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n", 5,
                       "second parent");
  expect_text_rejected("  <joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"zz\"/></joint>\n", 4,
                       "link 'zz', which is not declared");
  expect_text_rejected("  <joint name=\"j\" type=\"fixed\"><parent link=\"a\"/></joint>\n", 4, "no child link");
  expect_text_rejected("  <joint type=\"fixed\"/>\n", 4, "without a name");
  expect_text_rejected("  <joint name=\"j\"><parent link=\"a\"/><child link=\"b\"/></joint>\n", 4, "no type");
  expect_text_rejected("  <link name=\"c\"/>\n" + ab, 1, "root links");
  expect_text_rejected(
      "  <joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n"
      "    <limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/></joint>\n",
      5, "lower 1, upper -1");
  expect_text_rejected("  <joint name=\"j\" type=\"fixed\">\n  <parent link=\"a\"/>\n", 6, "not well-formed XML");
  // Fuzzers' finds: TinyXML read past the end of a truncated multi-byte sequence.
  expect_text_rejected("  <link name=\"c\xE5", 4, "not UTF-8");
  expect_text_rejected("  <link name=\"c\xC3\xA9\"/>\n  <!-- \xC0\xAF -->\n", 5, "not UTF-8");
  expect_text_rejected(std::string("  <link name=\"c\"/>\0<link name=\"d\"/>\n", 36), 4, "NUL byte");
}

TEST(UrdfImport, MissingFileIsNamed) {
  try {
    model_from_urdf_file(kFixtures + "no_such.urdf");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, kFixtures + "no_such.urdf");
    EXPECT_NE(e.problem().find("cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace avar::kinematics
