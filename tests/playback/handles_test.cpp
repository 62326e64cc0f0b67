// Blender's handle rules on small hand-checked curves (the golden test checks them against
// Blender itself on many more).
#include "avar/playback/offline/handles.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

RawKey typed(double t, double v, HandleType left, HandleType right) {
  RawKey k = key(t, v, Interpolation::bezier);
  k.left_type = left, k.right_type = right;
  return k;
}

TEST(Handles, VectorPointsAThirdOfTheWayToTheNeighbour) {
  const auto h = compute_handles(raw_curve({key(0, 0), typed(3, 6, HandleType::vector, HandleType::vector), key(9, 0)}));
  EXPECT_DOUBLE_EQ(h[1].left->time, 2);
  EXPECT_DOUBLE_EQ(h[1].left->value, 4);
  EXPECT_DOUBLE_EQ(h[1].right->time, 5);
  EXPECT_DOUBLE_EQ(h[1].right->value, 4);
}

TEST(Handles, AutoFollowsTheNeighboursAndReachesAboutAFifthOfTheInterval) {
  const auto h = compute_handles(raw_curve({key(0, 0), typed(1, 1, HandleType::automatic, HandleType::automatic), key(2, 2)}));
  // On a straight line the auto handles lie on it, |dt| = interval / 2.5614 (Blender's constant).
  EXPECT_NEAR(h[1].left->time, 1 - 1 / 2.5614, 1e-12);
  EXPECT_NEAR(h[1].left->value, 1 - 1 / 2.5614, 1e-12);
  EXPECT_NEAR(h[1].right->time, 1 + 1 / 2.5614, 1e-12);
  EXPECT_NEAR(h[1].right->value, 1 + 1 / 2.5614, 1e-12);
}

TEST(Handles, AutoClampedKeepsExtremesFlatAndAutoDoesNot) {
  const auto clamped = compute_handles(raw_curve({key(0, 0), typed(1, 5, HandleType::auto_clamped, HandleType::auto_clamped), key(3, 1)}));
  EXPECT_DOUBLE_EQ(clamped[1].left->value, 5);
  EXPECT_DOUBLE_EQ(clamped[1].right->value, 5);
  const auto free_auto = compute_handles(raw_curve({key(0, 0), typed(1, 5, HandleType::automatic, HandleType::automatic), key(3, 1)}));
  EXPECT_NE(free_auto[1].left->value, 5);
  // Left and right stay on one line through the key either way.
  const Handle l = *free_auto[1].left, r = *free_auto[1].right;
  EXPECT_NEAR((5 - l.value) / (1 - l.time), (r.value - 5) / (r.time - 1), 1e-12);
}

TEST(Handles, EndKeysLieFlatUnderConstantExtrapolationOnly) {
  RawCurve raw = raw_curve({typed(0, 0, HandleType::automatic, HandleType::automatic), typed(1, 4, HandleType::automatic, HandleType::automatic)});
  EXPECT_DOUBLE_EQ(compute_handles(raw)[0].right->value, 0);
  raw.extrapolation = Extrapolation::linear;
  EXPECT_GT(compute_handles(raw)[0].right->value, 0);
}

TEST(Handles, AlignedTurnsToContinueTheOtherSide) {
  RawKey k = typed(1, 1, HandleType::aligned, HandleType::vector);
  k.left = Handle{0.5, 3};  // keeps its length, takes the vector side's direction
  const auto h = compute_handles(raw_curve({key(0, 0), k, key(4, 4)}));
  EXPECT_DOUBLE_EQ(h[1].right->time, 2);
  EXPECT_DOUBLE_EQ(h[1].right->value, 2);
  const double length = std::hypot(0.5, 2.0);
  EXPECT_NEAR(h[1].left->time, 1 - length / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(h[1].left->value, 1 - length / std::sqrt(2.0), 1e-12);
}

TEST(Handles, TypesDefaultToFreeWithAHandleAndAutoClampedWithout) {
  RawKey with = key(0, 0);
  with.right = Handle{1, 1};
  EXPECT_EQ(right_type_of(with), HandleType::free);
  EXPECT_EQ(left_type_of(with), HandleType::auto_clamped);
  with.left_type = HandleType::vector;
  EXPECT_EQ(left_type_of(with), HandleType::vector);
}

TEST(Handles, CyclicCurvesGetHandlesAcrossTheCycle) {
  RawCurve raw = raw_curve({typed(0, 0, HandleType::automatic, HandleType::automatic), typed(1, 5, HandleType::automatic, HandleType::automatic),
                            typed(2, 0, HandleType::automatic, HandleType::automatic)});
  raw.cycles = Cycles{CycleMode::repeat, CycleMode::repeat, 0, 0};
  EXPECT_TRUE(cyclic_for_handles(raw.cycles));
  const auto h = compute_handles(raw);
  // The first key sees the second-to-last one a cycle earlier: a valley, so its handles stay
  // level, and the first and last keys get the same handles shifted by one cycle.
  EXPECT_NEAR(h[0].right->value - 0, h[2].right->value - 0, 1e-12);
  EXPECT_NEAR(h[0].right->time + 2, h[2].right->time, 1e-12);
  raw.cycles.after_count = 3;
  EXPECT_FALSE(cyclic_for_handles(raw.cycles));
}

}  // namespace
}  // namespace avar::playback
