#include "avar/kinematics/denavit_hartenberg.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "avar/kinematics/chain_text_reader.hpp"
#include "avar/kinematics/forward_kinematics.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d rot_z(double angle) { return Eigen::Isometry3d(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())); }

Eigen::Isometry3d tip_at(const Model& m, const std::vector<double>& q) {
  Workspace ws(m);
  EXPECT_EQ(forward_kinematics(m, q, ws), Status::ok);
  return effector_pose(m, ws, 0);
}

TEST(DenavitHartenberg, PlanarTwoLinkInBothConventionsMatchesTheClosedForm) {
  const double l1 = 0.3, l2 = 0.2;
  const std::vector<DhRow> standard{{l1, 0, 0, 0, -3, 3, {}}, {l2, 0, 0, 0, -3, 3, {}}};
  // Modified: each link length moves to the next row; the last one becomes the tool.
  const std::vector<DhRow> modified{{0, 0, 0, 0, -3, 3, {}}, {l1, 0, 0, 0, -3, 3, {}}};
  const Model s = chain_from_standard_dh(standard);
  const Model m = chain_from_modified_dh(modified, test::translation(l2, 0, 0));
  EXPECT_EQ(s.joint(1).name, "joint2");
  EXPECT_EQ(m.effector(0).name, "tip");
  const std::uint64_t seed = 11;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int sample = 0; sample < 100; ++sample) {
    const std::vector<double> q = test::random_configuration(s, rng);
    const Eigen::Vector3d expected(l1 * std::cos(q[0]) + l2 * std::cos(q[0] + q[1]), l1 * std::sin(q[0]) + l2 * std::sin(q[0] + q[1]), 0);
    EXPECT_TRUE(tip_at(s, q).translation().isApprox(expected, 1e-14));
    EXPECT_TRUE(tip_at(m, q).translation().isApprox(expected, 1e-14));
  }
}

TEST(DenavitHartenberg, ThetaIsAnOffsetOnTheJointVariable) {
  const std::vector<DhRow> rows{{1, 0, 0.5, kPi / 2, -1, 1, {}}};
  EXPECT_TRUE(tip_at(chain_from_standard_dh(rows), {0}).translation().isApprox(Eigen::Vector3d(0, 1, 0.5), 1e-15));
  EXPECT_TRUE(tip_at(chain_from_standard_dh(rows), {-kPi / 2}).translation().isApprox(Eigen::Vector3d(1, 0, 0.5), 1e-15));
}

using DenavitHartenbergOfBenchChains = test::BenchChains;

/// The UR5 in modified (Craig) DH, written out by hand: row i = (a_{i-1}, alpha_{i-1}, d_i, theta_i).
std::vector<DhRow> ur5_modified_dh() {
  const double two_pi = 2 * kPi;
  return {{0, 0, 0.089159, 0, -two_pi, two_pi, {}},        {0, kPi / 2, 0, 0, -two_pi, two_pi, {}},
          {-0.425, 0, 0, 0, -kPi, kPi, {}},                {-0.39225, 0, 0.10915, 0, -two_pi, two_pi, {}},
          {0, kPi / 2, 0.09465, 0, -two_pi, two_pi, {}},   {0, -kPi / 2, 0.0823, 0, -two_pi, two_pi, {}}};
}

TEST_F(DenavitHartenbergOfBenchChains, Ur5HomePoseIsTheKnownOneInBothConventions) {
  ASSERT_GE(chains.size(), 1u);
  ASSERT_EQ(chains[0].name, "ur5");
  const std::vector<double> home(6, 0.0);
  // All joints at zero: x = a2 + a3, y = -(d4 + d6), z = d1 - d5, the flange turned a quarter
  // turn about the base x axis.
  const Eigen::Vector3d position(-0.425 - 0.39225, -(0.10915 + 0.0823), 0.089159 - 0.09465);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (const Model& m : {chain_from_standard_dh(chains[0].rows), chain_from_modified_dh(ur5_modified_dh())}) {
    const Eigen::Isometry3d tip = tip_at(m, home);
    EXPECT_TRUE(tip.translation().isApprox(position, 1e-12)) << tip.translation().transpose();
    EXPECT_TRUE(tip.linear().isApprox(rotation, 1e-12)) << tip.linear();
  }
}

/// Builds `rows` in standard DH and, converted, in modified DH, and compares the two models at
/// random configurations.
void expect_conventions_agree(const std::vector<DhRow>& rows, std::mt19937_64& rng) {
  const test::ModifiedDh modified_rows = test::modified_from_standard(rows);
  const Model standard = chain_from_standard_dh(rows);
  const Model modified = chain_from_modified_dh(modified_rows.rows, modified_rows.tool);
  ASSERT_EQ(standard.dof(), rows.size());
  ASSERT_EQ(modified.dof(), rows.size());
  Workspace ws_s(standard), ws_m(modified);
  for (int sample = 0; sample < 100; ++sample) {
    const std::vector<double> q = test::random_configuration(standard, rng);
    ASSERT_EQ(forward_kinematics(standard, q, ws_s), Status::ok);
    ASSERT_EQ(forward_kinematics(modified, q, ws_m), Status::ok);
    EXPECT_TRUE(effector_pose(modified, ws_m, 0).isApprox(effector_pose(standard, ws_s, 0), 1e-12));
    // Both joint frames sit on the same joint axis: the modified (proximal) frame i is the
    // standard model's joint frame turned by theta_i and moved d_i along that axis.
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Eigen::Isometry3d expected = ws_s.joint_pose(i) * rot_z(rows[i].theta) * test::translation(0, 0, rows[i].d);
      EXPECT_TRUE(ws_m.joint_pose(i).isApprox(expected, 1e-12)) << "joint " << i + 1;
    }
  }
}

TEST_F(DenavitHartenbergOfBenchChains, StandardAndModifiedFormsOfTheSameArmAgree) {
  const std::uint64_t seed = 42;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (const DhChain& chain : chains) {
    SCOPED_TRACE(chain.name);
    expect_conventions_agree(chain.rows, rng);
  }
}

TEST(DenavitHartenberg, StandardAndModifiedFormsOfRandomArmsAgree) {
  const std::uint64_t seed = 43;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int arm = 0; arm < 20; ++arm) {
    SCOPED_TRACE("arm " + std::to_string(arm));
    std::vector<DhRow> rows(1 + arm % 7);
    for (DhRow& row : rows)
      row = {test::uniform(rng, -0.5, 0.5), test::uniform(rng, -kPi, kPi), test::uniform(rng, -0.5, 0.5),
             test::uniform(rng, -kPi, kPi), test::uniform(rng, -kPi, 0), test::uniform(rng, 0, kPi), {}};
    expect_conventions_agree(rows, rng);
  }
}

/// The message of the InputError that building a standard DH chain from `text` throws.
std::string chain_error(const std::string& text) {
  std::istringstream in(text);
  const std::vector<DhChain> chains = read_dh_chains(in, "arm.txt");
  try {
    chain_from_standard_dh(chains.at(0).rows);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DenavitHartenberg, ReportsBadValuesAtTheirRow) {
  EXPECT_EQ(chain_error("chain arm 2\n0 0 0 0 -1 1\n0 0 0 0 1 -1\n"),
            "arm.txt:3:1: joint 'joint2': expected finite limits with lower <= upper, found lower 1, upper -1");
  // The standard convention puts row 1's link parameters into joint 2's origin; the error
  // still names row 1.
  EXPECT_EQ(chain_error("chain arm 2\n  nan 0 0 0 -1 1\n0 0 0 0 -1 1\n"),
            "arm.txt:2:3: joint 'joint1': expected finite DH parameters, found a nan, alpha 0, d 0, theta 0");
  EXPECT_EQ(chain_error("chain arm 2\n0 0 0 0 -1 1\n0 inf 0 0 -1 1\n"),
            "arm.txt:3:1: joint 'joint2': expected finite DH parameters, found a 0, alpha inf, d 0, theta 0");
}

TEST(DenavitHartenberg, RefusesAnEmptyChain) {
  try {
    chain_from_modified_dh({});
    FAIL() << "an empty chain was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<input>: expected at least one DH row, found none");
  }
}

}  // namespace
}  // namespace avar::kinematics
