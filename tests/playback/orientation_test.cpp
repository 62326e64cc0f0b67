// Orientation: Euler <-> quaternion <-> matrix round trips in every order, the stated Euler
// convention, quaternion tracks that stay unit length, take the short way, and (squad) turn with
// continuous angular velocity through keys.
#include "avar/playback/runtime/orientation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace avar::playback {
namespace {

constexpr std::array<EulerOrder, 6> kOrders = {EulerOrder::xyz, EulerOrder::xzy, EulerOrder::yxz,
                                               EulerOrder::yzx, EulerOrder::zxy, EulerOrder::zyx};

Eigen::Quaterniond random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

TEST(Euler, StatedConventionXyzAppliesXFirstAboutFixedAxes) {
  const Eigen::Vector3d angles(0.3, -0.4, 1.1);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(matrix_from_euler(angles, EulerOrder::xyz).isApprox(expected, 1e-14));
  const Eigen::Matrix3d zyx = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
  EXPECT_TRUE(matrix_from_euler(angles, EulerOrder::zyx).isApprox(zyx, 1e-14));
  // A quarter turn about z maps x to y.
  EXPECT_TRUE((matrix_from_euler({0, 0, M_PI / 2}, EulerOrder::xyz) * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-14));
}

TEST(Euler, NamesRoundTrip) {
  for (EulerOrder o : kOrders) EXPECT_EQ(euler_order_from_name(to_string(o)), o);
  EXPECT_FALSE(euler_order_from_name("xyx").has_value());
}

TEST(Euler, RoundTripsInEveryOrder) {
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> outer(-M_PI + 1e-6, M_PI - 1e-6), middle(-M_PI / 2 + 1e-3, M_PI / 2 - 1e-3);
    for (EulerOrder o : kOrders) {
      // Angles in the canonical ranges come back exactly.
      Eigen::Vector3d angles;
      angles[0] = outer(rng);
      angles[1] = outer(rng);
      angles[2] = outer(rng);
      const auto middle_axis = static_cast<Eigen::Index>(std::string_view(to_string(o))[1] - 'x');
      angles[middle_axis] = middle(rng);
      const Eigen::Quaterniond q = quaternion_from_euler(angles, o);
      ASSERT_NEAR(q.norm(), 1.0, 1e-14);
      ASSERT_TRUE(euler_from_quaternion(q, o).isApprox(angles, 1e-8)) << "seed " << seed << " order " << to_string(o) << "\n"
                                                                        << euler_from_quaternion(q, o).transpose() << "\n"
                                                                        << angles.transpose();
      ASSERT_TRUE(matrix_from_euler(euler_from_matrix(q.toRotationMatrix(), o), o).isApprox(q.toRotationMatrix(), 1e-10));
      // Any rotation comes back as the same rotation.
      const Eigen::Quaterniond r = random_rotation(rng);
      ASSERT_LT(angle_between(quaternion_from_euler(euler_from_quaternion(r, o), o), r), 1e-9) << "seed " << seed;
    }
  }
}

TEST(Euler, GimbalLockStillGivesTheRotationBack) {
  for (EulerOrder o : kOrders) {
    Eigen::Vector3d angles(0.4, 0.7, -0.2);
    angles[static_cast<Eigen::Index>(std::string_view(to_string(o))[1] - 'x')] = M_PI / 2;
    const Eigen::Matrix3d r = matrix_from_euler(angles, o);
    EXPECT_TRUE(matrix_from_euler(euler_from_matrix(r, o), o).isApprox(r, 1e-9)) << to_string(o);
  }
}

TEST(QuaternionTrack, UnitLengthShortWayAndKeysHit) {
  for (auto mode : {OrientationInterpolation::slerp, OrientationInterpolation::squad}) {
    for (unsigned seed = 1; seed <= 30; ++seed) {
      std::mt19937 rng(seed);
      std::vector<QuaternionKey> keys;
      std::bernoulli_distribution flip(0.5);
      for (int i = 0; i < 6; ++i) {
        // Slerp: any rotations; squad: a random walk of turns up to 1.5 rad, as a real track has.
        Eigen::Quaterniond q = random_rotation(rng);
        if (mode == OrientationInterpolation::squad && i > 0) {
          std::uniform_real_distribution<double> turn(0.1, 1.5);
          const Eigen::Vector3d axis = random_rotation(rng).vec().normalized();
          q = keys.back().rotation.normalized() * Eigen::Quaterniond(Eigen::AngleAxisd(turn(rng), axis));
        }
        if (flip(rng)) q.coeffs() = -q.coeffs();  // the same rotation with the other sign
        q.coeffs() *= 1.0 + i;                    // not normalised: the track normalises
        keys.push_back({0.5 * i, q});
      }
      const QuaternionTrack track(keys, mode);
      for (std::size_t i = 0; i < keys.size(); ++i)
        ASSERT_LT(angle_between(track.evaluate(keys[i].time), keys[i].rotation.normalized()), 1e-9) << "seed " << seed;
      for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
        const double key_angle = angle_between(keys[i].rotation.normalized(), keys[i + 1].rotation.normalized());
        ASSERT_LE(key_angle, M_PI + 1e-12);
        const int steps = 100;
        double travelled = 0;
        Eigen::Quaterniond previous = track.evaluate(keys[i].time);
        for (int s = 1; s <= steps; ++s) {
          const Eigen::Quaterniond q = track.evaluate(keys[i].time + 0.5 * s / steps);
          ASSERT_NEAR(q.norm(), 1.0, 1e-12) << "seed " << seed;
          travelled += angle_between(previous, q);
          previous = q;
        }
        if (mode == OrientationInterpolation::slerp) {
          // Slerp turns the short way, along the great arc: the path is exactly the keys' angle.
          ASSERT_NEAR(travelled, key_angle, 1e-6) << "seed " << seed << " segment " << i;
        } else {
          // Squad bends towards its neighbours but never goes the long way round, which for keys
          // at most 1.5 rad apart would travel at least 2 pi - 1.5 > pi.
          ASSERT_LT(travelled, M_PI) << "seed " << seed << " segment " << i;
          ASSERT_GE(travelled, key_angle - 1e-9) << "seed " << seed << " segment " << i;
        }
      }
    }
  }
}

TEST(QuaternionTrack, SignFlipTakesTheShortWay) {
  // 170 degrees about z, given with the sign that would make a naive slerp go 190 degrees.
  Eigen::Quaterniond far(Eigen::AngleAxisd(170 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  far.coeffs() = -far.coeffs();
  const QuaternionTrack track({{0, Eigen::Quaterniond::Identity()}, {1, far}}, OrientationInterpolation::slerp);
  const Eigen::Quaterniond half = track.evaluate(0.5);
  EXPECT_NEAR(angle_between(half, Eigen::Quaterniond(Eigen::AngleAxisd(85 * M_PI / 180, Eigen::Vector3d::UnitZ()))), 0, 1e-12);
  EXPECT_GE(track.keys()[1].rotation.dot(track.keys()[0].rotation), 0);
}

/// Angular velocity (rad/s, world frame) at t by a central difference of the track.
Eigen::Vector3d angular_velocity(const QuaternionTrack& track, double t, double h) {
  const Eigen::Quaterniond delta = track.evaluate(t + h) * track.evaluate(t - h).conjugate();
  const Eigen::AngleAxisd aa(delta);
  return aa.axis() * aa.angle() / (2 * h);
}

TEST(QuaternionTrack, SquadIsC1AtKeysSlerpIsNot) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::vector<QuaternionKey> keys;
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    std::normal_distribution<double> n(0, 0.6);
    for (int i = 0; i < 5; ++i) {
      keys.push_back({1.0 * i, q});
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(std::abs(n(rng)) + 0.2, Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized()));
    }
    const QuaternionTrack squad(keys, OrientationInterpolation::squad);
    const double h = 1e-5;
    for (int k = 1; k <= 3; ++k) {
      const double t = keys[static_cast<std::size_t>(k)].time;
      const Eigen::Vector3d before = angular_velocity(squad, t - 2 * h, h);
      const Eigen::Vector3d after = angular_velocity(squad, t + 2 * h, h);
      ASSERT_LT((before - after).norm(), 1e-3 * (1 + before.norm())) << "seed " << seed << " key " << k;
    }
  }
  // Slerp through a bend: the angular velocity jumps at the middle key.
  const QuaternionTrack slerp({{0, Eigen::Quaterniond::Identity()},
                               {1, Eigen::Quaterniond(Eigen::AngleAxisd(1, Eigen::Vector3d::UnitX()))},
                               {2, Eigen::Quaterniond(Eigen::AngleAxisd(1, Eigen::Vector3d::UnitX())) *
                                       Eigen::Quaterniond(Eigen::AngleAxisd(1, Eigen::Vector3d::UnitY()))}},
                              OrientationInterpolation::slerp);
  EXPECT_GT((angular_velocity(slerp, 1 - 2e-5, 1e-5) - angular_velocity(slerp, 1 + 2e-5, 1e-5)).norm(), 0.5);
}

TEST(QuaternionTrack, EulerKeysInterpolateOnTheSphere) {
  const std::vector<EulerKey> keys = {{0, {0, 0, 0}}, {2, {0, 0, M_PI / 2}}};
  const QuaternionTrack track(keys, EulerOrder::xyz, OrientationInterpolation::slerp);
  EXPECT_TRUE(euler_from_quaternion(track.evaluate(1), EulerOrder::xyz).isApprox(Eigen::Vector3d(0, 0, M_PI / 4), 1e-12));
  EXPECT_LT(angle_between(track.evaluate(-1), Eigen::Quaterniond::Identity()), 1e-15);
}

TEST(QuaternionTrack, RejectsBadKeys) {
  using K = std::vector<QuaternionKey>;
  EXPECT_THROW(QuaternionTrack(K{}, OrientationInterpolation::slerp), std::invalid_argument);
  EXPECT_THROW(QuaternionTrack(K{{1, Eigen::Quaterniond::Identity()}, {1, Eigen::Quaterniond::Identity()}}, OrientationInterpolation::slerp),
               std::invalid_argument);
  EXPECT_THROW(QuaternionTrack(K{{0, Eigen::Quaterniond(0, 0, 0, 0)}}, OrientationInterpolation::squad), std::invalid_argument);
  EXPECT_THROW(QuaternionTrack(std::vector<EulerKey>{{0, {NAN, 0, 0}}}, EulerOrder::zyx, OrientationInterpolation::slerp),
               std::invalid_argument);
}

}  // namespace
}  // namespace avar::playback
