// Orientation keys as a show gives them: quaternion and Euler keys mixed in one track, unit
// length and the short way between keys, and bad keys rejected at their location.
#include "avar/playback/runtime/orientation_keys.hpp"

#include <gtest/gtest.h>

#include <random>
#include <cmath>
#include <string>

namespace avar::playback {
namespace {

OrientationKeySpec quaternion_key(double t, Eigen::Quaterniond q, int line = 3) {
  OrientationKeySpec k;
  k.time = t;
  k.quaternion = q;
  k.where = {"keys.yaml", line, 9};
  return k;
}

OrientationKeySpec euler_key(double t, Eigen::Vector3d xyz, int line = 3) {
  OrientationKeySpec k;
  k.time = t;
  k.euler = xyz;
  k.where = {"keys.yaml", line, 9};
  return k;
}

TEST(OrientationKeys, MixedKeysStayUnitLengthAndTurnTheShortWay) {
  const unsigned seed = 20261201;
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  for (auto interpolation : {OrientationInterpolation::slerp, OrientationInterpolation::squad}) {
    OrientationKeysSpec spec;
    spec.order = EulerOrder::zyx;
    spec.interpolation = interpolation;
    Eigen::Quaterniond walk = Eigen::Quaterniond::Identity();
    for (int i = 0; i < 8; ++i) {  // a random walk, each key within 1.2 rad of the previous
      walk = walk * Eigen::AngleAxisd(1.2 * std::uniform_real_distribution<double>(0, 1)(rng),
                                Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized());
      if (i % 2) spec.keys.push_back(quaternion_key(i, Eigen::Quaterniond(-walk.coeffs())));  // the far sign of the same rotation
      else spec.keys.push_back(euler_key(i, euler_from_quaternion(walk, spec.order)));
    }
    const OrientationKeyTrack track(spec);
    for (std::size_t i = 0; i < spec.keys.size(); ++i) {
      const Eigen::Quaterniond expected = spec.keys[i].quaternion ? *spec.keys[i].quaternion
                                                                  : quaternion_from_euler(spec.keys[i].euler, spec.order);
      EXPECT_LT(track.evaluate(spec.keys[i].time).angularDistance(expected), 1e-9) << "seed " << seed << " key " << i;
    }
    for (double t = -1; t < 8; t += 0.01) {
      const Eigen::Quaterniond q = track.evaluate(t), next = track.evaluate(t + 0.01);
      ASSERT_NEAR(q.norm(), 1, 1e-12) << "seed " << seed;
      ASSERT_LT(q.angularDistance(next), 0.05) << "seed " << seed << " t " << t;  // no long way round between keys
    }
    EXPECT_EQ(orientation_interpolation_from_name(to_string(interpolation)), interpolation);
  }
}

TEST(OrientationKeys, BadKeysAreRejectedAtTheKey) {
  const auto message = [](OrientationKeysSpec spec) {
    try {
      OrientationKeyTrack track(std::move(spec));
      return std::string();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  OrientationKeysSpec spec;
  spec.where = {"keys.yaml", 2, 5};
  EXPECT_EQ(message(spec), "keys.yaml:2:5: orientation keys: found none; expected at least one key");
  spec.keys = {euler_key(1, {0, 0, 0}), quaternion_key(1, Eigen::Quaterniond::Identity(), 7)};
  EXPECT_EQ(message(spec), "keys.yaml:7:9: orientation key time 1 s does not come after the previous key's 1 s; expected strictly increasing times");
  spec.keys = {quaternion_key(0, Eigen::Quaterniond(0, 0, 0, 0), 4)};
  EXPECT_EQ(message(spec), "keys.yaml:4:9: expected a quaternion [w, x, y, z] of finite numbers, not all 0");
  spec.keys = {euler_key(0, {std::nan(""), 0, 0}, 5)};
  EXPECT_EQ(message(spec), "keys.yaml:5:9: expected Euler angles [x, y, z] of finite numbers (radians)");
  EXPECT_EQ(orientation_interpolation_from_name("bezier"), std::nullopt);
}

}  // namespace
}  // namespace avar::playback
