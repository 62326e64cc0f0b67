// User distance-time curves: keys are honoured, names round trip, and curves that do not start at
// 0, end at 1 or that go back anywhere between keys are rejected at the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "avar/playback/runtime/distance_time.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

std::string rejection(const RawCurve& raw) {
  try {
    DistanceTime::from_keys(raw);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(UserDistanceTime, FollowsItsKeysAndStaysWithinTheUnitSquare) {
  const DistanceTime f = DistanceTime::from_keys(raw_curve({key(0, 0), key(0.5, 0.3), key(1, 1)}));
  EXPECT_EQ(f.shape(), DistanceTimeShape::user);
  EXPECT_DOUBLE_EQ(f.distance(0.25), 0.15);
  EXPECT_DOUBLE_EQ(f.distance(0.75), 0.65);
  EXPECT_EQ(f.distance(-1), 0);
  EXPECT_EQ(f.distance(2), 1);
  EXPECT_EQ(f.distance(std::nan("")), 0);
  EXPECT_NEAR(f.speed(0.25), 0.6, 1e-6);
  EXPECT_NEAR(f.speed(0.75), 1.4, 1e-6);
  EXPECT_EQ(f.user_keys().keys.size(), 3u);
}

TEST(UserDistanceTime, BuiltInShapeNamesRoundTrip) {
  for (DistanceTimeShape s : {DistanceTimeShape::linear, DistanceTimeShape::sine, DistanceTimeShape::sine_constant_middle,
                              DistanceTimeShape::parabolic, DistanceTimeShape::cubic})
    EXPECT_EQ(distance_time_shape_from_name(to_string(s)), s);
  EXPECT_EQ(distance_time_shape_from_name("user"), std::nullopt);
  EXPECT_EQ(distance_time_shape_from_name("quadratic"), std::nullopt);
}

TEST(UserDistanceTime, RejectsCurvesThatDoNotRiseFromZeroToOne) {
  EXPECT_EQ(rejection(raw_curve({key(0, 0.1, Interpolation::linear, {}, {}, 4), key(1, 1)})),
            "test.yaml:4:5: expected a user distance-time curve (normalised time -> normalised distance) to start with a key at "
            "time 0, value 0; found time 0, value 0.1");
  EXPECT_EQ(rejection(raw_curve({key(0, 0), key(0.8, 1, Interpolation::linear, {}, {}, 9)})),
            "test.yaml:9:5: expected a user distance-time curve (normalised time -> normalised distance) to end with a key at "
            "time 1, value 1; found time 0.8, value 1");
  EXPECT_NE(rejection(raw_curve({key(0, 0), key(0.5, 0.6, Interpolation::linear, {}, {}, 6), key(0.7, 0.4), key(1, 1)}))
                .find("test.yaml:6:5: expected a user distance-time curve (normalised time -> normalised distance) to rise from 0 "
                      "to 1 without ever going back, but between 0.5 and 0.7"),
            std::string::npos);
  // Keys that rise, but a Catmull-Rom segment between them that overshoots and comes back.
  const std::string overshoot =
      rejection(raw_curve({key(0, 0, Interpolation::catmull_rom), key(0.1, 0.9, Interpolation::catmull_rom, {}, {}, 5),
                           key(0.9, 0.95, Interpolation::catmull_rom), key(1, 1)}));
  EXPECT_NE(overshoot.find("test.yaml:5:5: expected a user distance-time curve"), std::string::npos) << overshoot;
}

}  // namespace
}  // namespace avar::playback
