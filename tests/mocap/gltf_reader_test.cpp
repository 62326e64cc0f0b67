#include "avar/mocap/gltf_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/input_errors.hpp"
#include "joint_positions.hpp"
#include "avar/core/input_error.hpp"

namespace avar::mocap {
namespace {

// Fixtures: tests/data/mocap/make_gltf_fixtures.py wrote them; expected positions are worked by
// hand below from the glTF 2.0 specification (node TRS, Appendix C interpolation).
std::string gltf_fixture(const std::string& name) { return testing::mocap_fixture(name); }

#define EXPECT_GLTF_AT(animation, frame, joint, x, y, z) EXPECT_JOINT_AT(animation, frame, joint, x, y, z, 1e-6)

TEST(GltfReaderFixtures, SkinJointsLinearSlerpAndStep) {
  const SkeletonAnimation a = load_gltf(gltf_fixture("gltf_linear_step_skin.gltf"));
  ASSERT_EQ(a.joints.size(), 3U);  // the mesh node carrying the skin is not a joint
  EXPECT_EQ(a.joints[0].name, "root");
  EXPECT_EQ(a.joints[2].parent, 1);
  EXPECT_EQ(a.frame_count(), 31U);  // keys end at 1 s: samples 0, 1/30 ... 30/30
  EXPECT_DOUBLE_EQ(a.frame_time, 1.0 / 30);
  EXPECT_EQ(a.channels[0], std::vector<std::string>{"translation:STEP"});
  EXPECT_EQ(a.channels[1], std::vector<std::string>{"rotation:LINEAR"});
  // t = 14/30: the STEP translation still holds its first key (0,1,0).
  EXPECT_GLTF_AT(a, 14, "root", 0, 1, 0);
  // t = 0.5: STEP takes key 1 (0,2,0); the arm's slerp is halfway, 45 deg about z:
  // hand = (0,2,0) + (1,0,0) + Rz45 (2,0,0) = (1 + sqrt2, 2 + sqrt2, 0).
  EXPECT_GLTF_AT(a, 15, "arm", 1, 2, 0);
  EXPECT_GLTF_AT(a, 15, "hand", 1 + std::sqrt(2.0), 2 + std::sqrt(2.0), 0);
  // t = 1: 90 deg: hand = (0,2,0) + (1,0,0) + (0,2,0).
  EXPECT_GLTF_AT(a, 30, "hand", 1, 4, 0);
}

TEST(GltfReaderFixtures, CubicSplineUnderAMatrixNodeWithBinFile) {
  const SkeletonAnimation a = load_gltf(gltf_fixture("gltf_cubic_matrix.gltf"));
  ASSERT_EQ(a.joints.size(), 2U);  // no skin: the animated node and its ancestor
  EXPECT_EQ(a.frame_count(), 61U);
  // base's matrix T(0,0,5) Rz(90) S(2) decomposes into its parts.
  EXPECT_LT((a.joints[0].rest_translation - Eigen::Vector3d(0, 0, 5)).norm(), 1e-12);
  EXPECT_LT((a.joints[0].rest_scale - Eigen::Vector3d(2, 2, 2)).norm(), 1e-12);
  EXPECT_LT((a.joints[0].rest_rotation.toRotationMatrix() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  // Hermite over td = 2 s from v0 = 0 (out-tangent b0 = 3) to v1 = 1 (in-tangent a1 = 0):
  // x(s) = td (s^3 - 2 s^2 + s) b0 + (-2 s^3 + 3 s^2) v1.
  // t = 0.5, s = 1/4: 2 * 0.140625 * 3 + 0.15625 = 1; world = (0,0,5) + Rz90 * 2 * (1,0,0) = (0,2,5).
  EXPECT_GLTF_AT(a, 15, "bone", 0, 2, 5);
  // t = 1, s = 1/2: 2 * 0.125 * 3 + 0.5 = 1.25 -> (0, 2.5, 5).
  EXPECT_GLTF_AT(a, 30, "bone", 0, 2.5, 5);
  EXPECT_GLTF_AT(a, 60, "bone", 0, 2, 5);
  EXPECT_GLTF_AT(a, 0, "bone", 0, 0, 5);
}

TEST(GltfReaderFixtures, GlbWithNormalizedShortRotations) {
  const SkeletonAnimation a = load_gltf(gltf_fixture("gltf_short_rotation.glb"), GltfReadOptions{10, 0});
  ASSERT_EQ(a.joints.size(), 2U);
  EXPECT_EQ(a.frame_count(), 11U);
  // Key 0 is w = -32768 -> max(-32768/32767, -1) = -1 (identity); key 1 (0, 23170, 0, 23170)/32767
  // normalises to 90 deg about y. Slerp the short way: 45 deg at t = 0.5.
  EXPECT_GLTF_AT(a, 0, "tip", 0, 0, 1);
  EXPECT_GLTF_AT(a, 5, "tip", std::sqrt(0.5), 0, std::sqrt(0.5));
  EXPECT_GLTF_AT(a, 10, "tip", 1, 0, 0);
}

TEST(GltfReaderFixtures, SparseAccessorWithoutBufferView) {
  const SkeletonAnimation a = load_gltf(gltf_fixture("gltf_sparse.gltf"), GltfReadOptions{4, 0});
  ASSERT_EQ(a.frame_count(), 5U);
  // Keys (0,0,0) and, by substitution, (4,0,0): linear, so (2,0,0) at t = 0.5; end 1 above it.
  EXPECT_GLTF_AT(a, 0, "end", 0, 1, 0);
  EXPECT_GLTF_AT(a, 2, "slider", 2, 0, 0);
  EXPECT_GLTF_AT(a, 2, "end", 2, 1, 0);
  EXPECT_GLTF_AT(a, 4, "end", 4, 1, 0);
}

std::string gltf_text(const std::string& name) {
  std::ifstream in(gltf_fixture(name));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string gltf_error(const std::string& text) {
  return ::avar::testing::load_error([](const std::string& path) { load_gltf(path); }, text, "broken.gltf");
}

TEST(GltfReaderErrors, RefusalsNameTheJsonPath) {
  using ::avar::testing::replace;
  const std::string good = gltf_text("gltf_linear_step_skin.gltf");
  EXPECT_EQ(gltf_error(good), "");
  EXPECT_EQ(gltf_error(replace(good, "\"output\": 1,", "\"output\": 99,")),
            ": animations[0].samplers[0].output: accessor 99 out of range (the file has 4)");
  EXPECT_EQ(gltf_error(replace(good, "\"interpolation\": \"LINEAR\"", "\"interpolation\": \"BEZIER\"")),
            ": animations[0].samplers[0].interpolation: 'BEZIER'; expected LINEAR, STEP or CUBICSPLINE");
  EXPECT_EQ(gltf_error(replace(good, "\"interpolation\": \"STEP\"", "\"interpolation\": \"CUBICSPLINE\"")),
            ": animations[0].samplers[1].output: 2 elements for 2 keys; expected 6 (CUBICSPLINE: in-tangent, value, "
            "out-tangent per key)");
  // Accessor 1 (the rotations, 8 floats) read as VEC3 makes 2 elements of the wrong type.
  EXPECT_EQ(gltf_error(replace(good, "\"type\": \"VEC4\"", "\"type\": \"VEC3\"")),
            ": animations[0].samplers[0].output: accessor 1 is VEC3; expected VEC4");
  EXPECT_EQ(gltf_error(replace(good, "\"node\": 1,", "\"node\": 7,")),
            ": animations[0].channels[0].target.node: node 7 out of range (the file has 4)");
  const std::string missing = gltf_error(replace(gltf_text("gltf_cubic_matrix.gltf"), "gltf_cubic_matrix.bin", "missing.bin"));
  EXPECT_EQ(missing.rfind(": not a readable glTF 2.0 file: ", 0), 0U) << missing;
  const std::string not_json = gltf_error("{ \"asset\": ");
  EXPECT_EQ(not_json.rfind(": not a readable glTF 2.0 file: ", 0), 0U) << not_json;
}

}  // namespace
}  // namespace avar::mocap
