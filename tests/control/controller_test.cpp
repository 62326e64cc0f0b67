// The controller's tick against an in-memory link: soft start from the present pose, the show,
// soft stop to rest, stop requests, faults, and limits that no show can break.
#include "avar/control/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../support/recording_link.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

using testing::RecordingLink;

Rig two_channel_rig() {
  Rig rig;
  rig.name = "test";
  rig.channels.push_back({.name = "jaw", .unit = "deg", .min = 0, .max = 30, .rest = 0, .max_velocity = 200, .max_acceleration = 2000, .max_jerk = 20000, .ramp_velocity = 20, .where = {}});
  rig.channels.push_back({.name = "pan", .unit = "deg", .min = -60, .max = 60, .rest = 10, .max_velocity = 300, .max_acceleration = 3000, .max_jerk = 30000, .ramp_velocity = 40, .where = {}});
  rig.links.emplace_back().name = "head";
  return rig;
}

playback::Track track(const std::string& channel, std::vector<std::pair<double, double>> keys) {
  playback::RawCurve raw;
  for (auto [t, v] : keys) {
    playback::RawKey k;
    k.time = t;
    k.value = v;
    raw.keys.push_back(k);
  }
  playback::Curve curve = playback::Curve::build(raw);
  return playback::Track{channel, raw, std::move(curve), {}};
}

playback::Show jaw_show() {
  playback::Show show;
  show.name = "jaw";
  show.duration = 2.0;
  show.tracks.push_back(track("jaw", {{0.0, 5.0}, {1.0, 25.0}, {2.0, 5.0}}));
  return show;
}

/// Runs the controller on a stepped clock until it finishes; returns the tick count.
int run(Controller& c, double dt, int max_ticks = 100000) {
  int k = 0;
  for (; c.active() && k < max_ticks; ++k) c.tick(k * dt);
  return k;
}

TEST(Controller, EasesInFromThePresentPosePlaysAndEasesOutToRest) {
  const Rig rig = two_channel_rig();
  const playback::Show show = jaw_show();
  RecordingLink link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  const std::vector<double> present{12.0, -30.0};
  c.begin(0.0, present);
  EXPECT_EQ(c.phase(), Phase::homing);
  run(c, 0.01);
  ASSERT_GT(link.frames.size(), 10u);
  // The first frame sent is (almost) where the figure was: no snap.
  EXPECT_NEAR(link.frames.front()[0], 12.0, 0.05);
  EXPECT_NEAR(link.frames.front()[1], -30.0, 0.05);
  // The last frame is the rest pose, reached with zero speed.
  EXPECT_DOUBLE_EQ(link.frames.back()[0], 0.0);
  EXPECT_DOUBLE_EQ(link.frames.back()[1], 10.0);
  const auto& a = link.frames[link.frames.size() - 2];
  EXPECT_NEAR(a[0], 0.0, 0.01);
  // The show's peak (a sharp corner at 25) was played, rounded by the acceleration and jerk
  // limits but never exceeded.
  double peak = 0;
  for (const auto& f : link.frames) peak = std::max(peak, f[0]);
  EXPECT_GT(peak, 23.0);
  EXPECT_LE(peak, 25.0);
  EXPECT_GE(c.show_start_time(), 0.25);
}

TEST(Controller, HomingGlidesToTheFirstFrameAndTheShowStartsThereAtRest) {
  const Rig rig = two_channel_rig();
  const playback::Show show = jaw_show();
  RecordingLink link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  // jaw 12 -> 5 at up to 20/s, pan -30 -> 10 (its rest: no track) at up to 40/s: the pan sets
  // the duration, 2 * 40 / 40 = 2 s, and the jaw glides slower to arrive with it.
  c.begin(0.0, std::vector<double>{12.0, -30.0});
  int k = 0;
  for (; c.phase() == Phase::homing && k < 1000; ++k) c.tick(k * 0.01);
  ASSERT_EQ(c.phase(), Phase::running);
  EXPECT_NEAR(c.show_start_time(), 2.0, 0.01 + 1e-9);
  // The show's first sample was taken with the figure already at rest on its first frame.
  const std::vector<double>& before_show = link.frames[link.frames.size() - 2];
  EXPECT_EQ(before_show, (std::vector<double>{5.0, 10.0}));
  double jaw_speed = 0, pan_speed = 0;
  for (std::size_t i = 1; i + 1 < link.frames.size(); ++i) {
    jaw_speed = std::max(jaw_speed, std::abs(link.frames[i][0] - link.frames[i - 1][0]) / 0.01);
    pan_speed = std::max(pan_speed, std::abs(link.frames[i][1] - link.frames[i - 1][1]) / 0.01);
  }
  EXPECT_NEAR(pan_speed, 40.0, 0.5);  // 2d/T: the ramp_velocity
  EXPECT_NEAR(jaw_speed, 7.0, 0.1);   // 2 * 7 / 2
}

TEST(Controller, StopRequestEasesToRestFromWhereverTheFigureIs) {
  const Rig rig = two_channel_rig();
  const playback::Show show = jaw_show();
  RecordingLink link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  c.begin(0.0, rig.rest_frame());
  int k = 0;
  for (; c.show_time() < 1.0 || c.phase() != Phase::running; ++k) c.tick(k * 0.01);
  const double at_stop = link.frames.back()[0];
  EXPECT_GT(at_stop, 20.0);
  c.request_stop(k * 0.01);
  EXPECT_EQ(c.phase(), Phase::stopping);
  for (; c.active(); ++k) c.tick(k * 0.01);
  EXPECT_DOUBLE_EQ(link.frames.back()[0], 0.0);
  // No jump at the moment of the stop.
  for (std::size_t i = 1; i < link.frames.size(); ++i) EXPECT_LE(std::abs(link.frames[i][0] - link.frames[i - 1][0]), 2.0 + 1e-9);
}

TEST(Controller, LinkFailureLatchesAFaultAndStopsSending) {
  const Rig rig = two_channel_rig();
  const playback::Show show = jaw_show();
  RecordingLink link;
  link.fail_from_send = 30;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  c.begin(0.0, rig.rest_frame());
  run(c, 0.01);
  EXPECT_EQ(c.phase(), Phase::faulted);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::link_failure);
  EXPECT_EQ(c.latched_fault().status, Status::io_error);
  EXPECT_EQ(link.frames.size(), 30u);
}

TEST(Controller, OtherLinksEaseToRestWhenOneFails) {
  Rig rig = two_channel_rig();
  rig.links.emplace_back().name = "body";
  const playback::Show show = jaw_show();
  RecordingLink good, bad;
  bad.fail_from_send = 80;
  Controller c(rig, show, {&good, &bad}, {.tick_period_s = 0.01});
  c.begin(0.0, rig.rest_frame());
  run(c, 0.01);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::link_failure);
  EXPECT_EQ(c.latched_fault().index, 1u);
  EXPECT_DOUBLE_EQ(good.frames.back()[0], 0.0);
  EXPECT_GT(good.frames.size(), bad.frames.size());
}

TEST(Controller, ReleaseNowLetsGoOfEveryLink) {
  const Rig rig = two_channel_rig();
  const playback::Show show = jaw_show();
  RecordingLink link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  c.begin(0.0, rig.rest_frame());
  c.tick(0);
  c.release_now();
  EXPECT_EQ(link.releases, 1);
  EXPECT_EQ(c.phase(), Phase::disabled);
}

// A show whose keys lie far outside the limits (as a show built in code, or a bad exporter,
// could produce) never makes the controller command outside [min, max] or faster than
// max_velocity: seeded random family.
TEST(Controller, ShowsBeyondTheLimitsNeverProduceOutOfRangeCommands) {
  const unsigned seed = 4242;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Rig rig = two_channel_rig();
  for (int family = 0; family < 50; ++family) {
    playback::Show show;
    show.name = "wild";
    show.duration = 3.0;
    for (const char* ch : {"jaw", "pan"}) {
      std::vector<std::pair<double, double>> keys;
      double t = 0;
      while (t < 3.0) {
        keys.emplace_back(t, -500 + 1000 * u(rng));
        t += 0.01 + 0.3 * u(rng);
      }
      show.tracks.push_back(track(ch, keys));
    }
    RecordingLink link;
    Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
    c.begin(0.0, rig.rest_frame());
    const double dt = 0.02;
    run(c, dt);
    std::vector<double> prev = rig.rest_frame();
    for (const auto& f : link.frames) {
      for (std::size_t i = 0; i < 2; ++i) {
        ASSERT_GE(f[i], rig.channels[i].min);
        ASSERT_LE(f[i], rig.channels[i].max);
        ASSERT_LE(std::abs(f[i] - prev[i]), rig.channels[i].max_velocity * dt + 1e-9);
      }
      prev = f;
    }
    EXPECT_GT(c.limiter().clamped(0), 0u);
  }
}

TEST(Controller, LoopingShowPlaysTheRequestedPasses) {
  const Rig rig = two_channel_rig();
  playback::Show show = jaw_show();
  show.loop = true;
  RecordingLink link;
  ControllerOptions options;
  options.loops = 3;
  options.tick_period_s = 0.01;
  Controller c(rig, show, {&link}, options);
  c.begin(0.0, rig.rest_frame());
  run(c, 0.01);
  EXPECT_NEAR(c.show_time(), 6.0, 0.011);
}

}  // namespace
}  // namespace avar::control

namespace avar::control {
namespace {

/// A show whose only motion is a clip on a layer driving `channel`: 20 (a held ramp's end).
playback::Show layered_show(const std::string& channel) {
  playback::Show show;
  show.name = "layered";
  show.duration = 2.0;
  playback::Clip clip;
  clip.name = "raise";
  clip.duration = 1;
  clip.tracks.push_back(track(channel, {{0.0, 20.0}}));
  show.clips.push_back(std::move(clip));
  playback::Layer layer;
  layer.name = "top";
  layer.placements.push_back({.clip = 0, .start = 0, .end = 2, .speed = 1, .offset = 0, .reverse = false, .fade_in = 0, .fade_out = 0, .where = {}});
  show.layers.push_back(std::move(layer));
  return show;
}

TEST(Controller, BindsTheChannelsOfClipsOnLayersByName) {
  const Rig rig = two_channel_rig();
  const playback::Show show = layered_show("pan");
  RecordingLink link;
  Controller c(rig, show, {&link}, {.tick_period_s = 0.01});
  c.begin(0.0, std::vector<double>{0.0, 10.0});
  run(c, 0.01);
  double pan_peak = 0;
  for (const auto& f : link.frames) pan_peak = std::max(pan_peak, f[1]);
  EXPECT_NEAR(pan_peak, 20.0, 1e-9);  // the layer moved pan from its rest 10 to 20
  EXPECT_THROW(Controller(rig, layered_show("tail"), {&link}, {.tick_period_s = 0.01}), std::invalid_argument);
}

}  // namespace
}  // namespace avar::control
