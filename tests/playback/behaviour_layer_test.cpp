// Behaviour layers in the sampler: the layer's value is a function of the seed and the show time
// alone (any sampling rate, seeks back and forth, loop wraps), it plays only over its span with
// smoothstep fades, keeps to its mask, blends additive (motion about rest) or override, and
// composes without allocating.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "../support/allocation_count.hpp"
#include "avar/playback/runtime/behaviour_player.hpp"
#include "avar/playback/runtime/sampler.hpp"

namespace avar::playback {
namespace {

const std::vector<std::string> kBehaviourFrame{"head", "tilt", "eyes", "lid", "jaw"};

/// head and eyes (gaze), tilt (breathing), lid (blinks); jaw is the generators' too, unused.
IdleSpec behaviour_test_spec() {
  IdleSpec spec;
  spec.limits = {{-60, 60, 0, 0, 180, 1800, 36000},
                 {-25, 30, 0, 2, 100, 1000, 20000},
                 {-35, 35, 1, 0, 400, 4000, 80000},
                 {0, 100, 0, 20, 1500, 60000, 3e6},
                 {0, 30, 0, 0, 300, 8000, 400000}};
  BlinkSpec b;
  b.lids = {{3, 80, 0}};
  b.interval_min = 0.8;
  b.interval_max = 1.5;
  spec.blinks = b;
  GazeSpec g;
  g.eyes_pan = 2;
  g.head_pan = 0;
  g.pan_min = -25;
  g.pan_max = 25;
  g.tilt_min = g.tilt_max = 0;
  g.fixation_min = 0.2;
  g.fixation_max = 0.8;
  spec.gaze = g;
  BreathingSpec br;
  br.channels = {{1, 3}};
  br.period_s = 2;
  spec.breathing = br;
  return spec;
}

Layer behaviour_test_layer(Blend blend, double weight, double from, double to, double fade_in, double fade_out) {
  Layer layer;
  layer.name = "life";
  layer.blend = blend;
  layer.weight = weight;
  LayerBehaviour b;
  b.seed = 7;
  b.from = from;
  b.to = to;
  b.fade_in = fade_in;
  b.fade_out = fade_out;
  b.idle = behaviour_test_spec();
  b.channels = kBehaviourFrame;
  layer.behaviour = b;
  return layer;
}

/// A show whose base track holds `jaw` and `tilt` at constants, under one behaviour layer.
Show behaviour_test_show(Layer layer, bool loop = false) {
  Show show;
  show.name = "behaviour";
  show.duration = 10;
  show.loop = loop;
  for (const auto& [channel, value] : {std::pair{"tilt", 5.0}, std::pair{"jaw", 12.0}}) {
    RawCurve raw;
    RawKey k;
    k.value = value;
    raw.keys.push_back(k);
    show.tracks.push_back({channel, raw, Curve::build(raw), {}});
  }
  show.layers.push_back(std::move(layer));
  return show;
}

std::vector<double> behaviour_test_defaults() { return {0, 2, 0, 20, 0}; }

std::vector<double> behaviour_sampled(Sampler& sampler, double t) {
  std::vector<double> frame(kBehaviourFrame.size());
  sampler.sample(t, frame);
  return frame;
}

TEST(BehaviourLayer, ValuesDependOnShowTimeAloneAtAnyRateAndUnderSeeks) {
  const Show show = behaviour_test_show(behaviour_test_layer(Blend::override, 1, 1, 9, 0.5, 0.5));
  // Monotonic at 100 Hz: the reference.
  Sampler reference(show, kBehaviourFrame, behaviour_test_defaults());
  std::vector<std::vector<double>> expected;
  for (int k = 0; k <= 1000; ++k) expected.push_back(behaviour_sampled(reference, k * 0.01));
  // At 1 kHz the same times give the same values, exactly.
  Sampler fast(show, kBehaviourFrame, behaviour_test_defaults());
  for (int k = 0; k <= 10000; ++k) {
    const double t = k % 10 == 0 ? (k / 10) * 0.01 : k * 0.001;  // the reference's times exactly
    const std::vector<double> frame = behaviour_sampled(fast, t);
    if (k % 10 == 0) {
      ASSERT_EQ(frame, expected[static_cast<std::size_t>(k / 10)]) << "t " << t;
    }
  }
  // Seeded families of seeks, back and forth: the same values again.
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    Sampler seeking(show, kBehaviourFrame, behaviour_test_defaults());
    for (int n = 0; n < 30; ++n) {
      const auto k = std::uniform_int_distribution<std::size_t>(0, 1000)(rng);
      ASSERT_EQ(behaviour_sampled(seeking, static_cast<double>(k) * 0.01), expected[k]) << "t " << static_cast<double>(k) * 0.01;
    }
  }
  // The behaviour moved: gaze, blinks and breathing all did something.
  double eyes_span = 0, lid_min = 100;
  for (const auto& f : expected) {
    eyes_span = std::max(eyes_span, std::abs(f[2]));
    lid_min = std::min(lid_min, f[3]);
  }
  EXPECT_GT(eyes_span, 5);
  EXPECT_LT(lid_min, 10);
}

TEST(BehaviourLayer, ALoopingShowRepeatsItsBehaviourEachPass) {
  const Show show = behaviour_test_show(behaviour_test_layer(Blend::override, 1, 0, 10, 0, 0), true);
  Sampler first(show, kBehaviourFrame, behaviour_test_defaults());
  std::vector<std::vector<double>> pass;
  for (int k = 0; k < 500; ++k) pass.push_back(behaviour_sampled(first, k * 0.02));
  // Playing on through two wraps: each pass as the first (up to the rounding of the wrapped time).
  Sampler looping(show, kBehaviourFrame, behaviour_test_defaults());
  for (int k = 0; k < 1500; ++k) {
    const double t = (k % 500) * 0.02 + 10.0 * (k / 500);
    const std::vector<double> frame = behaviour_sampled(looping, t);
    for (std::size_t c = 0; c < frame.size(); ++c)
      ASSERT_NEAR(frame[c], pass[static_cast<std::size_t>(k % 500)][c], 1e-9) << kBehaviourFrame[c] << " at " << t;
  }
}

TEST(BehaviourPlayer, ASeekBackRestartsFromTheStartAndStepsOnItsGrid) {
  BehaviourPlayer player(behaviour_test_spec(), 3);
  std::vector<double> frame(5);
  player.sample(2.0, frame);
  EXPECT_EQ(player.restarts(), 0u);
  EXPECT_EQ(player.steps(), 401u);  // grid points 0, 5 ms, ..., 2 s
  player.sample(2.5, frame);
  EXPECT_EQ(player.steps(), 501u);
  player.sample(1.0, frame);  // back: restart, 201 steps again
  EXPECT_EQ(player.restarts(), 1u);
  EXPECT_EQ(player.steps(), 702u);
}

TEST(BehaviourLayer, PlaysOnlyOverItsSpanWithSmoothstepFades) {
  const Layer layer = behaviour_test_layer(Blend::override, 1, 2, 6, 1, 0.5);
  const Show show = behaviour_test_show(layer);
  Sampler sampler(show, kBehaviourFrame, behaviour_test_defaults());
  BehaviourPlayer alone(layer.behaviour->idle, layer.behaviour->seed);
  const std::vector<double> below{0, 5, 0, 20, 12};  // defaults under the show's tracks
  for (int k = 0; k <= 800; ++k) {
    const double t = k * 0.01;
    const std::vector<double> frame = behaviour_sampled(sampler, t);
    const double w = span_weight(t, 2, 6, 1, 0.5);
    if (w == 0) {
      ASSERT_EQ(frame, below) << "t " << t;
      continue;
    }
    std::vector<double> values(5);
    alone.sample(t - 2, values);
    for (std::size_t c = 0; c < 4; ++c) ASSERT_NEAR(frame[c], below[c] + w * (values[c] - below[c]), 1e-12) << c << " at " << t;
    ASSERT_EQ(frame[4], 12) << "the generators do not drive the jaw";
  }
  EXPECT_DOUBLE_EQ(span_weight(2.5, 2, 6, 1, 0.5), 0.5);
}

TEST(BehaviourLayer, AMaskKeepsItToItsChannelsAndAdditiveAddsTheMotionAboutRest) {
  Layer masked = behaviour_test_layer(Blend::additive, 0.5, 0, 10, 0, 0);
  masked.mask = {{"tilt", {}}, {"lid", {}}};
  const Show additive = behaviour_test_show(masked);
  Layer over = masked;
  over.blend = Blend::override;
  const Show override_show = behaviour_test_show(over);
  Sampler add(additive, kBehaviourFrame, behaviour_test_defaults());
  Sampler ovr(override_show, kBehaviourFrame, behaviour_test_defaults());
  BehaviourPlayer alone(masked.behaviour->idle, masked.behaviour->seed);
  const IdleSpec& spec = masked.behaviour->idle;
  for (int k = 0; k <= 500; ++k) {
    const double t = k * 0.02;
    std::vector<double> values(5);
    for (std::size_t c = 0; c < 5; ++c) values[c] = spec.limits[c].rest;
    alone.sample(t, values);
    const std::vector<double> a = behaviour_sampled(add, t), o = behaviour_sampled(ovr, t);
    // Outside the mask: what lies below, exactly.
    for (const std::size_t c : {0u, 2u, 4u}) {
      ASSERT_EQ(a[c], behaviour_test_defaults()[c] + (c == 4 ? 12 : 0)) << c;
      ASSERT_EQ(o[c], a[c]) << c;
    }
    // tilt: 5 below (a track), breathing about rest 2; lid: 20 below (default), blinks about rest 20.
    ASSERT_NEAR(a[1], 5 + 0.5 * (values[1] - 2), 1e-12) << t;
    ASSERT_NEAR(o[1], 5 + 0.5 * (values[1] - 5), 1e-12) << t;
    ASSERT_NEAR(a[3], 20 + 0.5 * (values[3] - 20), 1e-12) << t;
    ASSERT_NEAR(o[3], 20 + 0.5 * (values[3] - 20), 1e-12) << t;
  }
}

TEST(BehaviourLayer, TheSamplerRefusesAnUnboundBehaviourAndAChannelTheFrameLacks) {
  Layer unbound = behaviour_test_layer(Blend::override, 1, 0, 10, 0, 0);
  unbound.behaviour->channels.clear();
  const Show a = behaviour_test_show(unbound);
  EXPECT_THROW(Sampler(a, kBehaviourFrame, behaviour_test_defaults()), std::invalid_argument);
  Layer renamed = behaviour_test_layer(Blend::override, 1, 0, 10, 0, 0);
  renamed.behaviour->channels[3] = "eyelid";
  const Show b = behaviour_test_show(renamed);
  EXPECT_THROW(Sampler(b, kBehaviourFrame, behaviour_test_defaults()), std::invalid_argument);
  EXPECT_EQ(behaviour_channels(behaviour_test_layer(Blend::override, 1, 0, 10, 0, 0)),
            (std::vector<std::string>{"head", "tilt", "eyes", "lid"}));
}

TEST(BehaviourLayer, ComposingAllocatesNothingEvenWhenSeekingBack) {
  const Show show = behaviour_test_show(behaviour_test_layer(Blend::additive, 0.8, 1, 9, 0.5, 0.5), true);
  Sampler sampler(show, kBehaviourFrame, behaviour_test_defaults());
  std::vector<double> frame(kBehaviourFrame.size());
  sampler.sample(0, frame);
  const long before = avar::testing::allocations.load();
  for (int k = 0; k < 3000; ++k) sampler.sample(k * 0.007, frame);  // wraps twice
  sampler.sample(3.0, frame);                                       // and seeks back
  EXPECT_EQ(avar::testing::allocations.load() - before, 0);
}

}  // namespace
}  // namespace avar::playback
