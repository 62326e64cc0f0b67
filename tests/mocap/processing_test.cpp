#include "avar/mocap/processing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "avar/mocap/bvh_reader.hpp"

namespace avar::mocap {
namespace {

/// One joint turning about z at `degrees_per_s`, frames at `rate` Hz for `seconds`, plus a child
/// one unit along x; optional seeded noise on the angle.
SkeletonAnimation processing_turn(double rate, double seconds, double degrees_per_s, double noise_deg = 0, unsigned seed = 1) {
  SkeletonAnimation a;
  a.source = "turn";
  Joint root;
  root.name = "root";
  Joint tip;
  tip.name = "tip";
  tip.parent = 0;
  tip.rest_translation = Eigen::Vector3d::UnitX();
  a.joints = {root, tip};
  a.frame_time = 1.0 / rate;
  std::mt19937 random(seed);
  std::normal_distribution<double> jitter(0, noise_deg);
  const auto frames = static_cast<std::size_t>(std::lround(seconds * rate)) + 1;
  for (std::size_t f = 0; f < frames; ++f) {
    Pose pose = rest_pose(a);
    const double degrees = degrees_per_s * static_cast<double>(f) / rate + (noise_deg > 0 ? jitter(random) : 0.0);
    pose.rotation[0] = Eigen::AngleAxisd(degrees * std::numbers::pi / 180, Eigen::Vector3d::UnitZ());
    a.frames.push_back(pose);
  }
  return a;
}

double processing_angle_deg(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.angle() * 180 / std::numbers::pi * (aa.axis().z() < 0 ? -1 : 1);
}

TEST(MocapProcessing, ResamplingFollowsTheMotionAndRoundTrips) {
  const SkeletonAnimation a = processing_turn(30, 2, 45);  // 0 .. 90 degrees
  const SkeletonAnimation fine = resample(a, 120);
  EXPECT_EQ(fine.frame_count(), 241U);
  EXPECT_DOUBLE_EQ(fine.frame_time, 1.0 / 120);
  // 7 Hz does not divide the grid: frame 5 is at 5/7 s, 32.142857 degrees (slerp of a uniform turn).
  const SkeletonAnimation odd = resample(a, 7);
  EXPECT_EQ(odd.frame_count(), 15U);
  EXPECT_NEAR(processing_angle_deg(odd.frames[5].rotation[0]), 45.0 * 5 / 7, 1e-9);
  // 30 -> 120 -> 30 gives the original frames back.
  const SkeletonAnimation back = resample(fine, 30);
  ASSERT_EQ(back.frame_count(), a.frame_count());
  for (std::size_t f = 0; f < a.frame_count(); ++f)
    EXPECT_LT(back.frames[f].rotation[0].angularDistance(a.frames[f].rotation[0]), 1e-9) << f;
  EXPECT_THROW(resample(a, 0), std::invalid_argument);
}

TEST(MocapProcessing, TrimKeepsTheRangeWithTimeZeroAtItsStart) {
  const SkeletonAnimation a = processing_turn(10, 2, 45);
  const SkeletonAnimation part = trim(a, 0.25, 1.0);
  EXPECT_EQ(part.frame_count(), 8U);  // 0.25, 0.35 ... 0.95
  EXPECT_NEAR(processing_angle_deg(part.frames[0].rotation[0]), 11.25, 1e-9);
  EXPECT_NEAR(processing_angle_deg(part.frames[7].rotation[0]), 45 * 0.95, 1e-9);
  EXPECT_EQ(trim(a, -5, 50).frame_count(), a.frame_count());  // clamped to the animation
  EXPECT_THROW(trim(a, 1, 0.5), std::invalid_argument);
}

TEST(MocapProcessing, SmoothingIsQuaternionAwareAcrossSignFlips) {
  // A steady pose stored with alternating quaternion signs (as a file may hold it): the filter
  // must see one hemisphere, so the pose survives; filtering raw components would average to ~0.
  SkeletonAnimation a = processing_turn(60, 1, 0);
  const Eigen::Quaterniond held(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()));
  for (std::size_t f = 0; f < a.frame_count(); ++f) {
    a.frames[f].rotation[0] = held;
    if (f % 2) a.frames[f].rotation[0].coeffs() *= -1;
  }
  const SkeletonAnimation smoothed = smooth(a, playback::SmoothingMethod::butterworth, 5);
  for (std::size_t f = 0; f < smoothed.frame_count(); ++f)
    EXPECT_LT(smoothed.frames[f].rotation[0].angularDistance(held), 1e-9) << f;
}

TEST(MocapProcessing, SmoothingReducesSeededNoiseOnARotation) {
  const unsigned seed = 7;
  const SkeletonAnimation clean = processing_turn(60, 2, 30);
  const SkeletonAnimation noisy = processing_turn(60, 2, 30, 2.0, seed);
  const SkeletonAnimation smoothed = smooth(noisy, playback::SmoothingMethod::gaussian, 3);
  double before = 0, after = 0;
  for (std::size_t f = 0; f < clean.frame_count(); ++f) {
    before += noisy.frames[f].rotation[0].angularDistance(clean.frames[f].rotation[0]);
    after += smoothed.frames[f].rotation[0].angularDistance(clean.frames[f].rotation[0]);
    EXPECT_NEAR(smoothed.frames[f].rotation[0].norm(), 1, 1e-12);
  }
  EXPECT_LT(after, before / 2) << "seed " << seed;
  EXPECT_THROW(smooth(noisy, playback::SmoothingMethod::gaussian, 30), std::invalid_argument);
}

TEST(MocapProcessing, FindsTheLoopOfAPeriodicMotion) {
  // 0.8 s period swing: frames 24 apart (at 30 Hz) hold the same pose; rounding picks among them.
  SkeletonAnimation a = processing_turn(30, 2, 0);
  for (std::size_t f = 0; f < a.frame_count(); ++f) {
    const double t = static_cast<double>(f) / 30;
    a.frames[f].rotation[0] = Eigen::AngleAxisd(0.5 * std::sin(2 * std::numbers::pi * t / 0.8), Eigen::Vector3d::UnitZ());
  }
  const LoopMatch loop = find_loop(a, 0.5);
  EXPECT_EQ((loop.last - loop.first) % 24, 0U) << loop.first << " .. " << loop.last;
  EXPECT_GE(loop.last - loop.first, 15U);  // at least 0.5 s
  EXPECT_LT(loop.distance, 1e-9);
  // A pose that never returns: the best pair is the nearest allowed, and its distance says how far.
  const SkeletonAnimation turn = processing_turn(30, 2, 45);
  const LoopMatch drift = find_loop(turn, 1);
  EXPECT_EQ(drift.last - drift.first, 30U);
  EXPECT_NEAR(drift.distance, 45 * std::numbers::pi / 180 / std::sqrt(2.0), 1e-9);
  EXPECT_THROW(find_loop(a, 10), std::invalid_argument);
}

}  // namespace
}  // namespace avar::mocap
