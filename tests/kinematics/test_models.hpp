#pragma once
// Models, configurations and reference chains shared by the kinematics tests.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "avar/kinematics/chain_text_reader.hpp"
#include "avar/kinematics/model.hpp"
#include "avar/kinematics/model_builder.hpp"

namespace avar::kinematics::test {

/// The IK benchmark's reference chains (UR5, iiwa7), committed beside the benchmark.
inline const std::string kBenchChainsPath = AVAR_SOURCE_DIR "/bench/data/ik-chains.txt";

/// Skips the test, naming the file, when the reference chains are not there.
class BenchChains : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kBenchChainsPath))
      GTEST_SKIP() << "the reference chain file (bench/data/ik-chains.txt) is missing: " << kBenchChainsPath;
    chains = read_dh_chains(kBenchChainsPath);
  }
  std::vector<DhChain> chains;
};

/// Uniform in [0, 1), the same on every platform: (x >> 11) * 2^-53.
inline double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

inline double uniform(std::mt19937_64& rng, double lo, double hi) { return lo + (hi - lo) * unit(rng); }

/// A configuration drawn uniformly within the model's limits.
inline std::vector<double> random_configuration(const Model& model, std::mt19937_64& rng) {
  std::vector<double> q(model.dof());
  for (std::size_t k = 0; k < q.size(); ++k) q[k] = uniform(rng, model.lower_limits()[k], model.upper_limits()[k]);
  return q;
}

inline Eigen::Isometry3d random_rigid(std::mt19937_64& rng, double reach) {
  Eigen::Quaterniond rotation(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  rotation.normalize();
  Eigen::Isometry3d t(rotation);
  t.translation() = Eigen::Vector3d(uniform(rng, -reach, reach), uniform(rng, -reach, reach), uniform(rng, -reach, reach));
  return t;
}

inline Eigen::Isometry3d translation(double x, double y, double z) { return Eigen::Isometry3d(Eigen::Translation3d(x, y, z)); }

/// A branched figure: a torso that slides along a tilted rail (prismatic), a neck, and an arm
/// (shoulder, a fixed mount, a second slide, an elbow), with effectors "head" and "hand".
inline Model branched_figure() {
  ModelBuilder b;
  Eigen::Isometry3d tilted(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  b.add_joint({"slide", JointType::prismatic, "", tilted, Eigen::Vector3d(0, 0.2, 1), -0.2, 0.2});
  b.add_joint({"neck", JointType::revolute, "slide", translation(0, 0, 0.4), Eigen::Vector3d(0, 0, 1), -1, 1});
  Eigen::Isometry3d shoulder_origin = translation(0.2, 0, 0.3);
  shoulder_origin.rotate(Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitX()));
  b.add_joint({"shoulder", JointType::revolute, "slide", shoulder_origin, Eigen::Vector3d(1, 1, 0), -2, 2});
  b.add_joint({"mount", JointType::fixed, "shoulder", translation(0, 0.1, 0), Eigen::Vector3d::Zero(), 0, 0});
  b.add_joint({"forearm", JointType::prismatic, "mount", translation(0.1, 0, 0), Eigen::Vector3d(1, 0, 0), 0, 0.15});
  b.add_joint({"elbow", JointType::revolute, "forearm", translation(0.25, 0, 0), Eigen::Vector3d(0, 1, 0), -2, 2});
  Eigen::Isometry3d palm = translation(0.2, 0, 0.05);
  palm.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  b.add_effector({"hand", "elbow", palm});
  b.add_effector({"head", "neck", translation(0.1, 0, 0.1)});
  return b.build();
}

/// A random tree of `joints` joints: random parents (or the base), types, origins, axes and
/// limits, with one effector "e<i>" at a random tool offset on every joint.
inline Model random_tree(std::mt19937_64& rng, std::size_t joints) {
  ModelBuilder b;
  for (std::size_t i = 0; i < joints; ++i) {
    JointSpec spec;
    spec.name = "j" + std::to_string(i);
    const auto parent = static_cast<std::size_t>(uniform(rng, 0, static_cast<double>(i) + 1));
    spec.parent = parent == i ? std::string() : "j" + std::to_string(parent);
    const double kind = unit(rng);
    spec.type = kind < 0.5 ? JointType::revolute : kind < 0.8 ? JointType::prismatic : JointType::fixed;
    spec.origin = random_rigid(rng, 0.3);
    do spec.axis = Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    while (spec.axis.norm() < 0.1);
    const double span = spec.type == JointType::prismatic ? 0.2 : std::numbers::pi;
    spec.lower = uniform(rng, -span, 0);
    spec.upper = uniform(rng, 0, span);
    b.add_joint(spec);
  }
  for (std::size_t i = 0; i < joints; ++i) b.add_effector({"e" + std::to_string(i), "j" + std::to_string(i), random_rigid(rng, 0.2)});
  return b.build();
}

/// Modified DH rows of the arm that standard DH `rows` describe, and the tool that puts the
/// modified chain's tip on the standard chain's last frame: modified row i takes a and alpha of
/// standard row i-1 (zero for the first), and the last row's a and alpha move into the tool.
struct ModifiedDh {
  std::vector<DhRow> rows;
  Eigen::Isometry3d tool;
};

inline ModifiedDh modified_from_standard(const std::vector<DhRow>& standard) {
  ModifiedDh out;
  double a = 0, alpha = 0;
  for (const DhRow& row : standard) {
    out.rows.push_back({a, alpha, row.d, row.theta, row.lower, row.upper, row.where});
    a = row.a;
    alpha = row.alpha;
  }
  out.tool = translation(a, 0, 0) * Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX());
  return out;
}

}  // namespace avar::kinematics::test
