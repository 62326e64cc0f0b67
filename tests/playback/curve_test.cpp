// Curve values at and between keys for each interpolation, extrapolation, and the errors of
// Curve::build with their locations.
#include "avar/playback/runtime/curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::build;
using testing::key;
using testing::raw_curve;

constexpr Interpolation kStep = Interpolation::step;
constexpr Interpolation kLinear = Interpolation::linear;
constexpr Interpolation kBezier = Interpolation::bezier;

TEST(Interpolation, NamesRoundTrip) {
  for (int i = 0; i <= static_cast<int>(Interpolation::bspline); ++i) {
    const auto interpolation = static_cast<Interpolation>(i);
    EXPECT_EQ(interpolation_from_name(to_string(interpolation)), interpolation);
  }
  EXPECT_EQ(std::string(to_string(kBezier)), "bezier");
  EXPECT_EQ(std::string(to_string(kStep)), "constant");
  EXPECT_EQ(interpolation_from_name("step"), kStep);
  EXPECT_FALSE(interpolation_from_name("cubic_bezier"));
  EXPECT_FALSE(interpolation_from_name("Linear"));
  EXPECT_FALSE(interpolation_from_name(""));
}

TEST(Curve, LinearHitsKeysAndInterpolatesBetween) {
  const Curve c = build({key(0, 0), key(1, 10), key(3, -10)});
  EXPECT_EQ(c.evaluate(0), 0);
  EXPECT_EQ(c.evaluate(1), 10);
  EXPECT_EQ(c.evaluate(3), -10);
  EXPECT_DOUBLE_EQ(c.evaluate(0.25), 2.5);
  EXPECT_DOUBLE_EQ(c.evaluate(0.5), 5);
  EXPECT_DOUBLE_EQ(c.evaluate(2), 0);
  EXPECT_DOUBLE_EQ(c.evaluate(2.5), -5);
  EXPECT_EQ(c.key_count(), 3u);
  EXPECT_EQ(c.start_time(), 0);
  EXPECT_EQ(c.end_time(), 3);
}

TEST(Curve, StepHoldsUntilTheNextKey) {
  const Curve c = build({key(0, 1, kStep), key(1, 5, kStep), key(2, 9)});
  EXPECT_EQ(c.evaluate(0), 1);
  EXPECT_EQ(c.evaluate(0.5), 1);
  EXPECT_EQ(c.evaluate(1 - 2 * Curve::kKeySnap), 1);
  // Within the key snap of the key, the key: a rounded key time is the key's.
  EXPECT_EQ(c.evaluate(std::nextafter(1.0, 0.0)), 5);
  EXPECT_EQ(c.evaluate(1 - 0.5 * Curve::kKeySnap), 5);
  EXPECT_EQ(c.evaluate(1), 5);
  EXPECT_EQ(c.evaluate(1.999), 5);
  EXPECT_EQ(c.evaluate(2), 9);
}

TEST(Curve, AKeysInterpolationShapesTheSegmentThatStartsAtIt) {
  // 0 -> 1 step, 1 -> 2 linear, 2 -> 3 step; the last key's interpolation shapes nothing.
  const Curve c = build({key(0, 0, kStep), key(1, 10, kLinear), key(2, 20, kStep), key(3, 30, kBezier)});
  EXPECT_EQ(c.evaluate(0.5), 0);
  EXPECT_DOUBLE_EQ(c.evaluate(1.5), 15);
  EXPECT_EQ(c.evaluate(2.5), 20);
  EXPECT_EQ(c.evaluate(3.5), 30);
}

TEST(Curve, ConstantExtrapolationOutsideTheKeys) {
  const Curve c = build({key(1, 3), key(2, 7)});
  EXPECT_EQ(c.evaluate(-100), 3);
  EXPECT_EQ(c.evaluate(0.5), 3);
  EXPECT_EQ(c.evaluate(2.5), 7);
  EXPECT_EQ(c.evaluate(1e9), 7);
  EXPECT_EQ(c.evaluate(-std::numeric_limits<double>::infinity()), 3);
  EXPECT_EQ(c.evaluate(std::numeric_limits<double>::infinity()), 7);
  EXPECT_EQ(c.evaluate(std::numeric_limits<double>::quiet_NaN()), 3);  // NaN counts as before the start
  const Curve one = build({key(0.5, 4)});
  EXPECT_EQ(one.evaluate(0), 4);
  EXPECT_EQ(one.evaluate(0.5), 4);
  EXPECT_EQ(one.evaluate(9), 4);
  EXPECT_EQ(one.key_count(), 1u);
}

TEST(Curve, DefaultCurveHasNoKeysAndIsZero) {
  const Curve c;
  CurveCursor cursor;
  EXPECT_EQ(c.key_count(), 0u);
  EXPECT_EQ(c.evaluate(-1), 0);
  EXPECT_EQ(c.evaluate(3, cursor), 0);
}

TEST(Curve, BezierSegmentsBetweenOtherInterpolations) {
  // Flat handles at a third of a 1 s segment: time runs linearly in u, so the value is the
  // smoothstep 10 (3u^2 - 2u^3) with u = t - 1.
  const Curve c = build({key(0, 0, kStep), key(1, 0, kBezier, {}, Handle{1 + 1.0 / 3, 0}), key(2, 10, kLinear, Handle{2 - 1.0 / 3, 10}),
                         key(3, 20)});
  EXPECT_EQ(c.evaluate(0.5), 0);
  for (double u = 0; u <= 1.0; u += 0.125) EXPECT_NEAR(c.evaluate(1 + u), 10 * (3 * u * u - 2 * u * u * u), 1e-12) << u;
  EXPECT_DOUBLE_EQ(c.evaluate(2.5), 15);
}

std::string error_of(const RawCurve& raw) {
  try {
    Curve::build(raw);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(Curve, RejectsBadKeysAtTheirLocation) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of(raw_curve({})), "test.yaml:1:3: the track has no keys; expected at least one key");
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kLinear, {}, {}, 4), key(2, 1, kLinear, {}, {}, 5), key(1.5, 2, kLinear, {}, {}, 6)})),
            "test.yaml:6:5: key time 1.5 s is not after the previous key's 2 s; key times must strictly increase");
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kLinear, {}, {}, 4), key(0, 1, kLinear, {}, {}, 5)})),
            "test.yaml:5:5: key time 0 s is not after the previous key's 0 s; key times must strictly increase");
  EXPECT_EQ(error_of(raw_curve({key(0, 0), key(nan, 1, kLinear, {}, {}, 7)})),
            "test.yaml:7:5: key time nan is not a number of seconds; expected a finite time");
  EXPECT_EQ(error_of(raw_curve({key(0, 0), key(0.5, inf, kLinear, {}, {}, 8)})),
            "test.yaml:8:5: key value inf at 0.5 s is not finite; expected a finite value");
  RawKey free_without_handle = key(0, 0, kBezier, {}, {}, 2);
  free_without_handle.right_type = HandleType::free;
  EXPECT_EQ(error_of(raw_curve({free_without_handle, key(1, 1, kLinear, Handle{0.5, 1}, {}, 3)})),
            "test.yaml:2:5: the right handle of the key at 0 s is free but not given; expected right: [time, value], or right_type "
            "auto, auto_clamped or vector to compute it");
  RawKey aligned_without_handle = key(1, 1, kLinear, {}, {}, 3);
  aligned_without_handle.left_type = HandleType::aligned;
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kBezier, {}, Handle{0.5, 0}, 2), aligned_without_handle})),
            "test.yaml:3:5: the left handle of the key at 1 s is aligned but not given; expected left: [time, value], or left_type "
            "auto, auto_clamped or vector to compute it");
  RawKey hermite = key(0, 0, Interpolation::hermite, {}, {}, 2);
  EXPECT_EQ(error_of(raw_curve({hermite, key(1, 1, kLinear, {}, {}, 3)})),
            "test.yaml:2:5: the key at 0 s starts a hermite segment but has no out_slope; expected out_slope: <units per second>");
  hermite.out_slope = 1;
  EXPECT_EQ(error_of(raw_curve({hermite, key(1, 1, kLinear, {}, {}, 3)})),
            "test.yaml:3:5: the key at 1 s ends a hermite segment but has no in_slope; expected in_slope: <units per second>");
  // Without handles or types, Bezier keys get Blender's default auto_clamped handles.
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kBezier), key(1, 1)})), "");
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kBezier, {}, Handle{nan, 0}, 2), key(1, 1, kLinear, Handle{0.5, 1}, {}, 3)})),
            "test.yaml:2:5: the right handle of the key at 0 s is [nan, 0]; expected a finite [time, value]");
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kBezier, {}, Handle{0.5, 0}, 2), key(1, 1, kLinear, Handle{0.5, -inf}, {}, 3)})),
            "test.yaml:3:5: the left handle of the key at 1 s is [0.5, -inf]; expected a finite [time, value]");
  RawCurve negative_cycles = raw_curve({key(0, 0), key(1, 1)});
  negative_cycles.cycles.after_count = -1;
  EXPECT_EQ(error_of(negative_cycles), "test.yaml:1:3: a cycle count is negative; expected 0 (forever) or more cycles");
  // Handles are not needed where no Bezier segment uses them, and then not checked for shape.
  EXPECT_EQ(error_of(raw_curve({key(0, 0, kLinear, {}, Handle{-3, 0}), key(1, 1, kStep)})), "");
}

}  // namespace
}  // namespace avar::playback
