// Blender's easing equations: every family and easing starts and ends on its keys, known values
// of Penner's equations, Blender's AUTO choice and its elastic defaults.
#include "avar/playback/runtime/easing.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace avar::playback {
namespace {

constexpr Interpolation kFamilies[] = {Interpolation::sine, Interpolation::quad,  Interpolation::cubic, Interpolation::quart,
                                       Interpolation::quint, Interpolation::expo, Interpolation::circ,  Interpolation::back,
                                       Interpolation::bounce, Interpolation::elastic};
constexpr Easing kEasings[] = {Easing::ease_in, Easing::ease_out, Easing::ease_in_out};

TEST(Easing, EveryFamilyStartsAndEndsOnItsKeys) {
  for (Interpolation f : kFamilies)
    for (Easing e : kEasings) {
      EXPECT_NEAR(ease(f, e, 0, 3, 10, 2, {}), 3, 1e-9) << to_string(f) << " " << to_string(e);
      EXPECT_NEAR(ease(f, e, 2, 3, 10, 2, {}), 13, 1e-9) << to_string(f) << " " << to_string(e);
      for (double t = 0; t <= 2; t += 0.01) EXPECT_TRUE(std::isfinite(ease(f, e, t, 3, 10, 2, {})));
    }
}

TEST(Easing, KnownValues) {
  EXPECT_DOUBLE_EQ(ease(Interpolation::quad, Easing::ease_in, 0.5, 0, 1, 1, {}), 0.25);
  EXPECT_DOUBLE_EQ(ease(Interpolation::quad, Easing::ease_out, 0.5, 0, 1, 1, {}), 0.75);
  EXPECT_DOUBLE_EQ(ease(Interpolation::cubic, Easing::ease_in_out, 0.25, 0, 1, 1, {}), 0.0625);
  EXPECT_NEAR(ease(Interpolation::sine, Easing::ease_in_out, 0.5, 0, 1, 1, {}), 0.5, 1e-15);
  EXPECT_NEAR(ease(Interpolation::bounce, Easing::ease_out, 1 / 2.75, 0, 1, 1, {}), 1, 1e-12);
  EXPECT_NEAR(ease(Interpolation::circ, Easing::ease_out, 0.5, 0, 1, 1, {}), std::sqrt(0.75), 1e-15);
  // Blender's expo is rescaled to start at exactly 0: 2^(10 (t - 1)) - 2^-10, over 1 - 2^-10.
  EXPECT_NEAR(ease(Interpolation::expo, Easing::ease_in, 0.5, 0, 1, 1, {}), (std::pow(2.0, -5) - std::pow(2.0, -10)) / (1 - std::pow(2.0, -10)),
              1e-15);
  // Back ease-in with s = 1.70158 dips about 10 % below the start.
  double lowest = 0;
  for (double t = 0; t <= 1; t += 0.001) lowest = std::min(lowest, ease(Interpolation::back, Easing::ease_in, t, 0, 1, 1, {}));
  EXPECT_NEAR(lowest, -0.1, 0.001);
}

TEST(Easing, BlendersAutomaticChoice) {
  EXPECT_EQ(resolved_easing(Interpolation::back, Easing::automatic), Easing::ease_out);
  EXPECT_EQ(resolved_easing(Interpolation::bounce, Easing::automatic), Easing::ease_out);
  EXPECT_EQ(resolved_easing(Interpolation::elastic, Easing::automatic), Easing::ease_out);
  EXPECT_EQ(resolved_easing(Interpolation::sine, Easing::automatic), Easing::ease_in);
  EXPECT_EQ(resolved_easing(Interpolation::expo, Easing::automatic), Easing::ease_in);
  EXPECT_EQ(resolved_easing(Interpolation::quad, Easing::ease_in_out), Easing::ease_in_out);
}

TEST(Easing, ElasticDefaultsAreBlenders) {
  for (double t = 0.05; t < 2; t += 0.05) {
    // Period 0 means 0.3 of the duration (2 s here).
    EXPECT_NEAR(ease(Interpolation::elastic, Easing::ease_out, t, 0, 10, 2, {1.70158, 10, 0}),
                ease(Interpolation::elastic, Easing::ease_out, t, 0, 10, 2, {1.70158, 10, 0.6}), 1e-12)
        << t;
    // Amplitude 0 (below the change): Blender's elastic blend fades the oscillation out within a
    // quarter period (0.15 s) of the start, after which the segment rests on its end value.
    if (t > 0.15) {
      EXPECT_NEAR(ease(Interpolation::elastic, Easing::ease_out, t, 0, 10, 2, {1.70158, 0, 0}), 10, 1e-12) << t;
    }
  }
}

}  // namespace
}  // namespace avar::playback
