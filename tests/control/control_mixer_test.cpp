#include "avar/control/control_mixer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace avar::control {
namespace {

constexpr double kMixDt = 0.01;

TEST(ControlMixer, AnOverrideLayerCrossfadesOverTheShowAndBack) {
  ControlMixer mixer(1, {{"jaw", 0, 10, Blend::override, 0.5, 0}});
  std::vector<double> frame{0};
  mixer.mix(frame, 0);
  mixer.set(0, 10, 0);
  double t = 0;
  // Halfway through the crossfade the eased weight is exactly one half.
  for (; t < 0.25 - 1e-9; t += kMixDt) {
    frame[0] = 0;
    mixer.mix(frame, t + kMixDt);
  }
  EXPECT_NEAR(frame[0], 5.0, 1e-9);
  for (; t < 1.0; t += kMixDt) {
    frame[0] = 0;
    mixer.mix(frame, t + kMixDt);
    mixer.set(0, 10, t + kMixDt);
  }
  EXPECT_DOUBLE_EQ(frame[0], 10.0);
  mixer.release(0);
  for (int k = 0; k < 50; ++k) {
    t += kMixDt;
    frame[0] = 0;
    mixer.mix(frame, t);
  }
  EXPECT_DOUBLE_EQ(frame[0], 0.0);
  EXPECT_FALSE(mixer.active(0));
}

TEST(ControlMixer, HigherPriorityWinsWhateverTheDeclarationOrder) {
  ControlMixer mixer(1, {{"top", 0, 20, Blend::override, 0, 0}, {"low", 0, 5, Blend::override, 0, 0}});
  std::vector<double> frame{1};
  mixer.set(0, 3, 0);
  mixer.set(1, 7, 0);
  mixer.mix(frame, 0);
  EXPECT_DOUBLE_EQ(frame[0], 3.0);
  mixer.release(0);
  frame[0] = 1;
  mixer.mix(frame, 0.01);
  EXPECT_DOUBLE_EQ(frame[0], 7.0);
}

TEST(ControlMixer, AdditiveLayersAddTheirWeightedOffsetOnTopOfAnOverride) {
  ControlMixer mixer(2, {{"offset", 1, 20, Blend::additive, 0, 0}, {"take", 1, 10, Blend::override, 0, 0}});
  std::vector<double> frame{4, 4};
  mixer.set(0, 2.5, 0);
  mixer.set(1, 10, 0);
  mixer.mix(frame, 0);
  EXPECT_DOUBLE_EQ(frame[0], 4.0);  // another channel is untouched
  EXPECT_DOUBLE_EQ(frame[1], 12.5);
}

TEST(ControlMixer, ASilentLayerReleasesAfterItsTimeout) {
  ControlMixer mixer(1, {{"pad", 0, 10, Blend::override, 0, 0.5}});
  std::vector<double> frame{0};
  mixer.set(0, 1, 0);
  mixer.mix(frame, 0.49);
  EXPECT_TRUE(mixer.active(0));
  EXPECT_DOUBLE_EQ(frame[0], 1.0);
  frame[0] = 0;
  mixer.mix(frame, 0.51);
  EXPECT_FALSE(mixer.active(0));
  EXPECT_DOUBLE_EQ(frame[0], 0.0);
}

TEST(ControlMixer, UpdateMovesAnActiveLayerWithoutKeepingItAlive) {
  ControlMixer mixer(1, {{"pad", 0, 10, Blend::override, 0, 0.5}});
  std::vector<double> frame{0};
  mixer.update(0, 9);  // inactive: ignored
  mixer.mix(frame, 0);
  EXPECT_DOUBLE_EQ(frame[0], 0.0);
  mixer.set(0, 1, 0);
  mixer.update(0, 2);
  mixer.mix(frame, 0.4);
  EXPECT_DOUBLE_EQ(frame[0], 2.0);
  mixer.update(0, 3);
  frame[0] = 0;
  mixer.mix(frame, 0.6);
  EXPECT_DOUBLE_EQ(frame[0], 0.0);
}

// Property: whatever the layers do (random takes and releases, random values following smooth
// signals), with smooth inputs the mixed output moves at most by a bound set by the crossfades:
// no jump at any hand-over.
TEST(ControlMixer, HandOversAreContinuousOverSeededRandomTakesAndReleases) {
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> fade(0.1, 1.0);
    ControlMixer mixer(1, {{"a", 0, 1, Blend::override, fade(rng), 0},
                           {"b", 0, 2, Blend::override, fade(rng), 0},
                           {"c", 0, 3, Blend::additive, fade(rng), 0}});
    const double dt = 0.001;
    double shortest = 1;
    for (std::size_t i = 0; i < mixer.size(); ++i) shortest = std::min(shortest, mixer.layer(i).crossfade_s);
    // Values within [-10, 10] whose slope is at most 30 /s.
    const double range = 20, slope = 30;
    // Eased weight moves at most 1.5 dt / crossfade per step; a value moves at most slope dt.
    const double bound = static_cast<double>(mixer.size()) * (1.5 * dt / shortest * range + slope * dt) + slope * dt + 1e-9;
    std::vector<double> frame{0};
    double last = 0;
    std::bernoulli_distribution flip(0.002);
    std::vector<bool> on(mixer.size(), false);
    // Each control's signal moves only while it is held (a released stick stays where it was).
    std::vector<double> held_time(mixer.size(), 0);
    for (int k = 0; k < 5000; ++k) {
      const double t = k * dt;
      for (std::size_t i = 0; i < mixer.size(); ++i) {
        if (flip(rng)) on[i] = !on[i];
        if (on[i]) {
          held_time[i] += dt;
          mixer.set(i, 10 * std::sin(held_time[i] * (1.0 + static_cast<double>(i))), t);
        } else {
          mixer.release(i);
        }
      }
      frame[0] = 10 * std::cos(t);
      mixer.mix(frame, t);
      if (k > 0) {
        ASSERT_LE(std::abs(frame[0] - last), bound) << "seed " << seed << " at " << t << " s";
      }
      last = frame[0];
      for (std::size_t i = 0; i < mixer.size(); ++i) ASSERT_GE(mixer.weight(i), 0.0) << "seed " << seed;
    }
  }
}

TEST(ControlMixer, RefusesLayersOnMissingChannelsOrWithNegativeTimes) {
  EXPECT_THROW(ControlMixer(1, {{"x", 1, 0, Blend::override, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(ControlMixer(1, {{"x", 0, 0, Blend::override, -1, 0}}), std::invalid_argument);
  EXPECT_THROW(ControlMixer(1, {{"x", 0, 0, Blend::override, 0, -1}}), std::invalid_argument);
}

TEST(ControlMixer, FindsLayersByName) {
  ControlMixer mixer(1, {{"x", 0, 0, Blend::override, 0, 0}});
  EXPECT_EQ(mixer.find("x"), 0u);
  EXPECT_EQ(mixer.find("y"), 1u);
}

}  // namespace
}  // namespace avar::control
