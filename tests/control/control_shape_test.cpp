#include "avar/control/control_shape.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace avar::control {
namespace {

TEST(ControlShape, PassesANormalisedValueThroughByDefault) {
  EXPECT_DOUBLE_EQ(shape_control(-0.25, true, {}).value, -0.25);
  EXPECT_DOUBLE_EQ(shape_control(0.75, false, {}).value, 0.75);
  EXPECT_TRUE(shape_control(0.1, true, {}).bipolar);
}

TEST(ControlShape, ClampsToTheControlsRangeAndReadsNonFiniteAsRest) {
  EXPECT_DOUBLE_EQ(shape_control(3, true, {}).value, 1.0);
  EXPECT_DOUBLE_EQ(shape_control(-3, false, {}).value, 0.0);
  EXPECT_DOUBLE_EQ(shape_control(std::numeric_limits<double>::quiet_NaN(), true, {}).value, 0.0);
}

TEST(ControlShape, InvertsBipolarAboutZeroAndUnipolarAboutOneHalf) {
  ControlShape s;
  s.invert = true;
  EXPECT_DOUBLE_EQ(shape_control(0.3, true, s).value, -0.3);
  EXPECT_DOUBLE_EQ(shape_control(0.3, false, s).value, 0.7);
}

TEST(ControlShape, TheDeadZoneReadsZeroAndRescalesTheRestToStayContinuous) {
  ControlShape s;
  s.dead_zone = 0.2;
  EXPECT_DOUBLE_EQ(shape_control(0.15, true, s).value, 0.0);
  EXPECT_DOUBLE_EQ(shape_control(-0.2, true, s).value, 0.0);
  EXPECT_NEAR(shape_control(0.6, true, s).value, 0.5, 1e-12);
  EXPECT_NEAR(shape_control(-1.0, true, s).value, -1.0, 1e-12);
  EXPECT_NEAR(shape_control(0.2 + 1e-9, false, s).value, 0.0, 1e-8);
}

TEST(ControlShape, ExpoIsFinerNearRestAndKeepsTheEnds) {
  ControlShape s;
  s.expo = 1;
  EXPECT_NEAR(shape_control(0.5, true, s).value, 0.125, 1e-12);
  EXPECT_NEAR(shape_control(-1, true, s).value, -1, 1e-12);
  s.expo = 0.5;
  EXPECT_NEAR(shape_control(0.5, false, s).value, 0.5 * 0.5 + 0.5 * 0.125, 1e-12);
}

TEST(ControlShape, AnInputRangeMakesTheControlUnipolar) {
  ControlShape s;
  s.input = std::pair{0.0, 127.0};
  const ShapedValue v = shape_control(63.5, true, s);
  EXPECT_FALSE(v.bipolar);
  EXPECT_NEAR(v.value, 0.5, 1e-12);
  s.input = std::pair{10.0, -10.0};  // reversed spans work too
  EXPECT_NEAR(shape_control(-10, false, s).value, 1.0, 1e-12);
}

TEST(ControlShape, IsMonotoneOverItsRangeForEveryShape) {
  for (double dz : {0.0, 0.1, 0.5})
    for (double expo : {0.0, 0.3, 1.0})
      for (bool bipolar : {true, false}) {
        ControlShape s;
        s.dead_zone = dz;
        s.expo = expo;
        double last = -2;
        for (double x = bipolar ? -1 : 0; x <= 1.0; x += 0.001) {
          const double y = shape_control(x, bipolar, s).value;
          ASSERT_GE(y, last - 1e-15) << "dz " << dz << " expo " << expo << " at " << x;
          last = y;
        }
      }
}

}  // namespace
}  // namespace avar::control
