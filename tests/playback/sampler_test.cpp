#include "avar/playback/runtime/sampler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::track;


Track ramp(const std::string& channel, double t0, double v0, double t1, double v1) { return track(channel, {key(t0, v0), key(t1, v1)}); }

TEST(Sampler, WritesEveryChannelWithDefaultsForUndrivenOnes) {
  Show show;
  show.duration = 2;
  show.tracks.push_back(ramp("b", 0, 0, 2, 20));
  show.tracks.push_back(track("d", {key(0, 1, Interpolation::step), key(1, 2)}));
  const std::vector<std::size_t> binding{1, 3};
  const std::vector<double> defaults{7, 0, 9, 0};
  Sampler sampler(show, binding, defaults);
  EXPECT_EQ(sampler.frame_size(), 4u);
  std::vector<double> frame(4, -1);
  sampler.sample(0.5, frame);
  EXPECT_EQ(frame, (std::vector<double>{7, 5, 9, 1}));
  sampler.sample(1.5, frame);
  EXPECT_EQ(frame, (std::vector<double>{7, 15, 9, 2}));
}

TEST(Sampler, AShowPlayedOnceHoldsItsEndsOutsideItsDuration) {
  Show show;
  show.duration = 2;
  show.tracks.push_back(ramp("a", 0.5, 1, 1.5, 3));
  Sampler sampler(show, std::vector<std::size_t>{0}, std::vector<double>{0});
  std::vector<double> frame(1);
  sampler.sample(-1, frame);
  EXPECT_EQ(frame[0], 1);
  sampler.sample(1, frame);
  EXPECT_DOUBLE_EQ(frame[0], 2);
  sampler.sample(5, frame);
  EXPECT_EQ(frame[0], 3);
}

TEST(Sampler, LoopingShowsWrapAtTheirDuration) {
  Show show;
  show.duration = 2;
  show.loop = true;
  show.tracks.push_back(ramp("a", 0, 0, 2, 20));
  Sampler sampler(show, std::vector<std::size_t>{0}, std::vector<double>{0});
  std::vector<double> frame(1);
  const std::pair<double, double> expected[] = {{0.5, 5}, {2.5, 5}, {7.0, 10}, {0.5, 5}, {1999.25, 12.5}, {-0.5, 15}, {-4.25, 17.5}, {2.0, 0}};
  for (auto [t, v] : expected) {
    sampler.sample(t, frame);
    EXPECT_NEAR(frame[0], v, 1e-9) << t;
  }
}

TEST(Sampler, EqualsTheCurvesAtEverySampleOverRandomTimes) {
  const unsigned seed = 31;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Show show;
  show.duration = 10;
  show.loop = true;
  for (int c = 0; c < 3; ++c) {
    std::vector<RawKey> keys;
    for (double t = 0; t <= 10; t += 0.1 + u(rng)) {
      const double v = 100 * u(rng);
      keys.push_back(key(t, v, static_cast<Interpolation>(rng() % 3), Handle{t - 0.2, v + 5}, Handle{t + 0.2, v - 5}));
    }
    show.tracks.push_back(track("c" + std::to_string(c), keys));
  }
  Sampler sampler(show, std::vector<std::size_t>{2, 0, 3}, std::vector<double>{0, 0, 0, 0, -1});
  std::vector<double> frame(5);
  double t = 0;
  for (int s = 0; s < 20000; ++s) {
    t = rng() % 50 == 0 ? -30 + 60 * u(rng) : t + 0.001;
    sampler.sample(t, frame);
    double wrapped = std::fmod(t, 10);
    if (wrapped < 0) wrapped += 10;
    ASSERT_EQ(frame[2], show.tracks[0].curve.evaluate(wrapped)) << t;
    ASSERT_EQ(frame[0], show.tracks[1].curve.evaluate(wrapped)) << t;
    ASSERT_EQ(frame[3], show.tracks[2].curve.evaluate(wrapped)) << t;
    ASSERT_EQ(frame[1], 0);
    ASSERT_EQ(frame[4], -1);
  }
}

TEST(Sampler, NoNaNEvenForNonFiniteTimes) {
  Show show;
  show.duration = 3;
  show.loop = true;
  show.tracks.push_back(ramp("a", 0, 4, 3, 6));
  Sampler sampler(show, std::vector<std::size_t>{0}, std::vector<double>{0});
  std::vector<double> frame(1);
  for (double t : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    sampler.sample(t, frame);
    EXPECT_TRUE(std::isfinite(frame[0])) << t;
  }
}

TEST(Sampler, SamplingAllocatesNothing) {
  Show show;
  show.duration = 60;
  show.loop = true;
  for (int c = 0; c < 8; ++c) {
    std::vector<RawKey> keys;
    for (int k = 0; k <= 60; ++k)
      keys.push_back(key(k, c + k % 7, Interpolation::bezier, Handle{k - 0.3, c + k % 7 - 1.0}, Handle{k + 0.3, c + k % 7 + 1.0}));
    show.tracks.push_back(track("c" + std::to_string(c), keys));
  }
  // Every other interpolation, with linear extrapolation and Cycles, on the remaining channels.
  for (int c = 0; c < 2; ++c) {
    std::vector<RawKey> keys;
    for (int k = 0; k <= 60; ++k) {
      RawKey rk = key(k, (k * 37 % 11) - 5.0, static_cast<Interpolation>(k % (static_cast<int>(Interpolation::bspline) + 1)));
      rk.in_slope = 1, rk.out_slope = -1;
      keys.push_back(rk);
    }
    RawCurve raw = testing::raw_curve(keys);
    raw.extrapolation = Extrapolation::linear;
    raw.cycles = Cycles{CycleMode::mirror, CycleMode::repeat_offset, 0, 0};
    Curve curve = Curve::build(raw);
    show.tracks.push_back(Track{"e" + std::to_string(c), std::move(raw), std::move(curve), {}});
  }
  Sampler sampler(show, std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, std::vector<double>(10, 0));
  std::vector<double> frame(10);
  const long before = avar::testing::allocations.load();
  for (int tick = -20000; tick < 200000; ++tick) sampler.sample(tick * 0.001, frame);
  EXPECT_EQ(avar::testing::allocations.load(), before);
}

TEST(Sampler, AFrameOfTheWrongSizeIsLeftUntouched) {
  Show show;
  show.duration = 1;
  show.tracks.push_back(ramp("a", 0, 0, 1, 1));
  Sampler sampler(show, std::vector<std::size_t>{1}, std::vector<double>{5, 5});
  std::vector<double> frame(1, -7);
  sampler.sample(0.5, frame);
  EXPECT_EQ(frame[0], -7);
}

std::string rejection(const Show& show, std::vector<std::size_t> binding, std::vector<double> defaults) {
  try {
    Sampler sampler(show, binding, defaults);
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

TEST(Sampler, RejectsBadBindings) {
  Show show;
  show.duration = 1;
  show.tracks.push_back(ramp("a", 0, 0, 1, 1));
  show.tracks.push_back(ramp("b", 0, 0, 1, 1));
  EXPECT_EQ(rejection(show, {0}, {0, 0}), "the show has 2 tracks but 1 channel indices were given; expected one per track");
  EXPECT_EQ(rejection(show, {0, 2}, {0, 0}), "track 'b' is bound to frame index 2; expected an index below the frame size 2");
  EXPECT_EQ(rejection(show, {1, 1}, {0, 0}),
            "track 'b' is bound to frame index 1, which another track already drives; expected one track per channel");
  EXPECT_EQ(rejection(show, {0, 1}, {0, std::numeric_limits<double>::quiet_NaN()}),
            "the default of frame index 1 is not finite; expected a finite value");
  EXPECT_EQ(rejection(show, {1, 0}, {0, 0, 3}), "");
}

}  // namespace
}  // namespace avar::playback

namespace avar::playback {
namespace {

TEST(Sampler, SamplingALayeredShowAllocatesNothing) {
  Show show;
  show.duration = 30;
  show.loop = true;
  show.tracks.push_back(track("c0", {key(0, 0, Interpolation::bezier), key(30, 10)}));
  for (int c = 0; c < 3; ++c) {
    Clip clip;
    clip.name = "clip" + std::to_string(c);
    clip.duration = 2 + c;
    clip.mode = static_cast<ClipMode>(c);
    for (int ch = 0; ch < 4; ++ch) {
      std::vector<RawKey> keys;
      for (int k = 0; k <= 8; ++k) keys.push_back(key(clip.duration * k / 8, (k * 7 + ch) % 5, Interpolation::bezier));
      clip.tracks.push_back(track("c" + std::to_string((ch + c) % 5), keys));
    }
    show.clips.push_back(std::move(clip));
  }
  for (int l = 0; l < 3; ++l) {
    Layer layer;
    layer.name = "l" + std::to_string(l);
    layer.blend = l == 1 ? Blend::additive : Blend::override;
    if (l == 2) layer.mask = {{"c1", {}}, {"c3", {}}};
    for (int p = 0; p < 6; ++p) {
      Placement placement;
      placement.clip = static_cast<std::size_t>((p + l) % 3);
      placement.start = p * 5;
      placement.end = p * 5 + 6.5 > 30 ? 30 : p * 5 + 6.5;
      placement.fade_in = placement.fade_out = 1;
      placement.speed = 0.5 + p * 0.25;
      placement.reverse = p % 2 == 1;
      layer.placements.push_back(placement);
    }
    show.layers.push_back(std::move(layer));
  }
  const std::vector<std::string> names{"c0", "c1", "c2", "c3", "c4"};
  Sampler sampler(show, names, std::vector<double>(5, 1));
  std::vector<double> frame(5);
  const long before = avar::testing::allocations.load();
  for (int tick = -2000; tick < 70000; ++tick) sampler.sample(tick * 0.001, frame);
  EXPECT_EQ(avar::testing::allocations.load(), before);
  for (double v : frame) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace avar::playback
