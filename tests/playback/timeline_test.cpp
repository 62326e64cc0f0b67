// Clips, layers and time: clip modes, time warps, crossfade weights and continuity, override and
// additive blending, and masks, through the sampler that plays them.
#include "avar/playback/runtime/timeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/playback/runtime/sampler.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::track;


/// A clip whose channels each ramp linearly from `from` to `to` over its duration.
Clip ramp_clip(const std::string& name, double duration, ClipMode mode, std::vector<std::string> channels, double from, double to) {
  Clip clip;
  clip.name = name;
  clip.duration = duration;
  clip.mode = mode;
  for (const auto& c : channels) clip.tracks.push_back(track(c, {key(0, from), key(duration, to)}));
  return clip;
}

Placement placed(std::size_t clip, double start, double end, double fade_in = 0, double fade_out = 0) {
  Placement p;
  p.clip = clip;
  p.start = start;
  p.end = end;
  p.fade_in = fade_in;
  p.fade_out = fade_out;
  return p;
}

Layer layer(std::string name, Blend blend, std::vector<Placement> placements, std::vector<std::string> mask = {}) {
  Layer l;
  l.name = std::move(name);
  l.blend = blend;
  l.placements = std::move(placements);
  for (auto& m : mask) l.mask.push_back({m, {}});
  return l;
}

std::vector<double> frame_at(Sampler& sampler, double t) {
  std::vector<double> frame(sampler.frame_size());
  sampler.sample(t, frame);
  return frame;
}

TEST(Clip, HoldLoopAndPingPongMapPlayedTimeIntoTheClip) {
  Clip clip = ramp_clip("c", 2, ClipMode::hold, {"a"}, 0, 20);
  const std::pair<double, double> hold[] = {{-1, 0}, {0, 0}, {0.5, 0.5}, {2, 2}, {7, 2}};
  for (auto [played, local] : hold) EXPECT_DOUBLE_EQ(clip.local_time(played), local) << played;
  clip.mode = ClipMode::loop;
  const std::pair<double, double> loop[] = {{0.5, 0.5}, {2.5, 0.5}, {5.25, 1.25}, {-0.5, 1.5}, {4, 0}};
  for (auto [played, local] : loop) EXPECT_DOUBLE_EQ(clip.local_time(played), local) << played;
  clip.mode = ClipMode::ping_pong;
  const std::pair<double, double> ping[] = {{0.5, 0.5}, {2, 2}, {2.5, 1.5}, {3.75, 0.25}, {4.5, 0.5}, {-0.5, 0.5}, {6.5, 1.5}};
  for (auto [played, local] : ping) EXPECT_DOUBLE_EQ(clip.local_time(played), local) << played;
  EXPECT_EQ(clip.local_time(std::nan("")), 0);
  EXPECT_EQ(clip.local_time(INFINITY), 2);
}

TEST(Clip, ModesGiveTheClipsValuesThroughTheSampler) {
  for (ClipMode mode : {ClipMode::hold, ClipMode::loop, ClipMode::ping_pong}) {
    SCOPED_TRACE(to_string(mode));
    Show show;
    show.duration = 10;
    show.clips.push_back(ramp_clip("c", 2, mode, {"a"}, 0, 20));
    show.layers.push_back(layer("l", Blend::override, {placed(0, 1, 10)}));
    const std::vector<std::string> names{"a"};
    Sampler sampler(show, names, std::vector<double>{-5});
    EXPECT_EQ(frame_at(sampler, 0.5)[0], -5);  // before the placement: the default
    EXPECT_DOUBLE_EQ(frame_at(sampler, 1.5)[0], 5);
    const double at_3_5 = mode == ClipMode::hold ? 20 : mode == ClipMode::loop ? 5 : 15;
    EXPECT_DOUBLE_EQ(frame_at(sampler, 3.5)[0], at_3_5);
  }
}

TEST(Placement, SpeedOffsetAndReverseWarpClipTime) {
  Show show;
  show.duration = 10;
  show.clips.push_back(ramp_clip("c", 4, ClipMode::hold, {"a"}, 0, 40));  // value = 10 × clip time
  Placement p = placed(0, 2, 10);
  p.speed = 2;
  p.offset = 1;
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 2), 1);
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 2.5), 2);
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 4), 4);  // held at the end
  p.reverse = true;
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 2), 3);
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 2.5), 2);
  EXPECT_DOUBLE_EQ(p.clip_time(show.clips[0], 9), 0);
  show.layers.push_back(layer("l", Blend::override, {p}));
  const std::vector<std::string> names{"a"};
  Sampler sampler(show, names, std::vector<double>{0});
  EXPECT_DOUBLE_EQ(frame_at(sampler, 2.25)[0], 25);
  EXPECT_DOUBLE_EQ(frame_at(sampler, 3)[0], 10);
}

TEST(Placement, WeightsFadeAlongASmoothstepAndACrossfadeSumsToOne) {
  const Placement out = placed(0, 0, 5, 0, 2);
  const Placement in = placed(0, 3, 8, 2, 0);
  EXPECT_EQ(out.weight(-0.1), 0);
  EXPECT_EQ(out.weight(0), 1);
  EXPECT_EQ(out.weight(3), 1);
  EXPECT_DOUBLE_EQ(out.weight(4), 0.5);
  EXPECT_EQ(out.weight(5), 0);
  EXPECT_DOUBLE_EQ(in.weight(3.5), smoothstep(0.25));
  EXPECT_DOUBLE_EQ(smoothstep(0.25), 0.15625);
  for (double t = 3; t <= 5; t += 0.01) EXPECT_NEAR(out.weight(t) + in.weight(t), 1, 1e-12) << t;
}

TEST(Layer, ACrossfadeIsContinuousOverADenseSweep) {
  // Two clips far apart in value, crossfading over 1 s, over a base track: no step between
  // samples may exceed what the steepest contribution allows.
  Show show;
  show.duration = 10;
  show.tracks.push_back(track("a", {key(0, 0), key(10, 10)}));
  show.clips.push_back(ramp_clip("low", 6, ClipMode::loop, {"a"}, -30, -10));
  show.clips.push_back(ramp_clip("high", 3, ClipMode::ping_pong, {"a"}, 40, 60));
  show.layers.push_back(layer("perf", Blend::override, {placed(0, 1, 5, 0.5, 1), placed(1, 4, 9, 1, 0.75)}));
  const std::vector<std::string> names{"a"};
  Sampler sampler(show, names, std::vector<double>{0});
  // Slope bound: the clips move ≤ 20/3 units/s; a smoothstep weight at most 1.5/fade per second
  // across a value gap of at most 90 units.
  const double h = 1e-4;
  const double bound = (20.0 / 3 + 1.5 / 0.5 * 90) * h * 1.01;
  double previous = frame_at(sampler, 0)[0];
  double worst = 0;
  for (double t = h; t <= 10; t += h) {
    const double v = frame_at(sampler, t)[0];
    worst = std::max(worst, std::abs(v - previous));
    ASSERT_LE(std::abs(v - previous), bound) << "at " << t;
    previous = v;
  }
  EXPECT_GT(worst, 0);
  // Inside the crossfade the weights sum to one: the value is the weighted mix, the base unseen.
  const double t = 4.5;
  const double w_low = show.layers[0].placements[0].weight(t), w_high = show.layers[0].placements[1].weight(t);
  EXPECT_NEAR(w_low + w_high, 1, 1e-12);
  const double low = show.clips[0].tracks[0].curve.evaluate(show.layers[0].placements[0].clip_time(show.clips[0], t));
  const double high = show.clips[1].tracks[0].curve.evaluate(show.layers[0].placements[1].clip_time(show.clips[1], t));
  EXPECT_NEAR(frame_at(sampler, t)[0], w_low * low + w_high * high, 1e-9);
}

TEST(Layer, OverrideBlendsTowardsItsValueAndAdditiveAddsOffsets) {
  Show show;
  show.duration = 4;
  show.tracks.push_back(track("a", {key(0, 10)}));
  show.tracks.push_back(track("b", {key(0, 10)}));
  show.clips.push_back(ramp_clip("const", 4, ClipMode::hold, {"a", "b"}, 30, 30));
  Layer over = layer("over", Blend::override, {placed(0, 0, 4)}, {"a"});
  over.weight = 0.25;
  Layer add = layer("add", Blend::additive, {placed(0, 0, 4)}, {"b"});
  add.weight = 0.5;
  show.layers = {over, add};
  const std::vector<std::string> names{"a", "b"};
  Sampler sampler(show, names, std::vector<double>{0, 0});
  const auto f = frame_at(sampler, 1);
  EXPECT_DOUBLE_EQ(f[0], 10 + 0.25 * (30 - 10));
  EXPECT_DOUBLE_EQ(f[1], 10 + 0.5 * 30);
  EXPECT_EQ(apply_blend(Blend::override, 2, 6, 0.5), 4);
  EXPECT_EQ(apply_blend(Blend::additive, 2, 6, 0.5), 5);
}

TEST(Layer, LayersApplyBottomToTop) {
  Show show;
  show.duration = 4;
  show.clips.push_back(ramp_clip("ten", 4, ClipMode::hold, {"a"}, 10, 10));
  show.clips.push_back(ramp_clip("one", 4, ClipMode::hold, {"a"}, 1, 1));
  show.layers = {layer("add", Blend::additive, {placed(1, 0, 4)}), layer("over", Blend::override, {placed(0, 0, 4)})};
  const std::vector<std::string> names{"a"};
  Sampler sampler(show, names, std::vector<double>{0});
  EXPECT_EQ(frame_at(sampler, 1)[0], 10);  // the override on top hides the offset below
  std::swap(show.layers[0], show.layers[1]);
  Sampler swapped(show, names, std::vector<double>{0});
  EXPECT_EQ(frame_at(swapped, 1)[0], 11);
}

TEST(Layer, MasksTouchOnlyTheirChannelsOverSeededRandomLayers) {
  const unsigned seed = 20261201;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<std::string> names{"c0", "c1", "c2", "c3", "c4", "c5"};
  for (int family = 0; family < 40; ++family) {
    Show show;
    show.duration = 10;
    for (int c = 0; c < 4; ++c) {
      std::vector<std::string> channels;
      for (const auto& n : names)
        if (u(rng) < 0.6) channels.push_back(n);
      if (channels.empty()) channels.push_back(names[rng() % names.size()]);
      show.clips.push_back(ramp_clip("k" + std::to_string(c), 0.5 + 3 * u(rng), static_cast<ClipMode>(rng() % 3), channels,
                                     -50 + 100 * u(rng), -50 + 100 * u(rng)));
    }
    // The bottom layer: unmasked, every clip; the top one masked to a random subset.
    std::vector<Placement> all;
    for (std::size_t c = 0; c < show.clips.size(); ++c) {
      const double start = 8 * u(rng);
      all.push_back(placed(c, start, start + 0.5 + (10 - start - 0.5) * u(rng), 0.2, 0.2));
    }
    std::vector<std::string> mask;
    for (const auto& n : names)
      if (u(rng) < 0.4) mask.push_back(n);
    if (mask.empty()) mask.push_back(names[0]);
    show.layers.push_back(layer("bottom", Blend::override, all));
    Show masked = show;
    masked.layers.push_back(layer("top", rng() % 2 ? Blend::additive : Blend::override, all, mask));
    Sampler without(show, names, std::vector<double>(names.size(), 3));
    Sampler with(masked, names, std::vector<double>(names.size(), 3));
    for (double t = -0.5; t <= 10.5; t += 0.01) {
      const auto a = frame_at(without, t);
      const auto b = frame_at(with, t);
      for (std::size_t c = 0; c < names.size(); ++c) {
        if (std::find(mask.begin(), mask.end(), names[c]) != mask.end()) continue;
        ASSERT_EQ(a[c], b[c]) << "family " << family << ", channel " << names[c] << " outside the mask changed at " << t;
      }
    }
  }
}

TEST(Sampler, LayeredShowsNeedChannelNamesAndEveryNamedChannel) {
  Show show;
  show.duration = 2;
  show.clips.push_back(ramp_clip("c", 2, ClipMode::hold, {"a"}, 0, 1));
  show.layers.push_back(layer("l", Blend::override, {placed(0, 0, 2)}, {"a", "zz"}));
  const auto rejection = [&](auto&&... args) -> std::string {
    try {
      Sampler sampler(show, args...);
      return "";
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
  };
  EXPECT_EQ(rejection(std::vector<std::size_t>{}, std::vector<double>{0}),
            "the show has layers of clips; expected the sampler to be given the frame's channel names to bind them");
  EXPECT_EQ(rejection(std::vector<std::string>{"a", "b"}, std::vector<double>{0, 0}),
            "the mask of layer 'l' names channel 'zz', which the frame does not have; expected one of: a, b");
  show.layers[0].mask.clear();
  EXPECT_EQ(rejection(std::vector<std::string>{"b"}, std::vector<double>{0}),
            "clip 'c' names channel 'a', which the frame does not have; expected one of: b");
  EXPECT_EQ(rejection(std::vector<std::string>{"a"}, std::vector<double>{0, 0}),
            "1 frame channel names but 2 defaults were given; expected one default per channel");
  EXPECT_EQ(rejection(std::vector<std::string>{"b", "a"}, std::vector<double>{0, 0}), "");
}

}  // namespace
}  // namespace avar::playback
