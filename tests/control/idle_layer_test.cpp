// Arbitration: idle life below the show, live inputs above it, the supervisor above all. The
// hand-over both ways is eased (bounded step per tick), the show wins its channels while it
// plays, a higher layer wins at weight 1, masks keep each layer to its channels, and an e-stop
// takes every channel to its fail-safe whatever the layers ask.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "../support/allocation_count.hpp"
#include "../support/recording_link.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/idle_layer.hpp"
#include "avar/control/layer_stack.hpp"
#include "avar/control/live_inputs.hpp"

namespace avar::control {
namespace {

/// jaw (the show drives it), pan (idle noise), lid (idle blinks).
rig::Rig idle_layer_rig() {
  rig::Rig rig;
  rig.name = "idle-layer";
  rig.channels.push_back({.name = "jaw",
                          .unit = "deg",
                          .min = 0,
                          .max = 30,
                          .rest = 0,
                          .max_velocity = 200,
                          .max_acceleration = 4000,
                          .max_jerk = 200000,
                          .ramp_velocity = 30,
                          .where = {}});
  rig.channels.push_back({.name = "pan",
                          .unit = "deg",
                          .min = -60,
                          .max = 60,
                          .rest = 0,
                          .max_velocity = 90,
                          .max_acceleration = 900,
                          .max_jerk = 20000,
                          .ramp_velocity = 30,
                          .where = {}});
  rig.channels.push_back({.name = "lid",
                          .unit = "%",
                          .min = 0,
                          .max = 100,
                          .rest = 80,
                          .max_velocity = 1500,
                          .max_acceleration = 60000,
                          .max_jerk = 3e6,
                          .ramp_velocity = 100,
                          .where = {}});
  rig.links.emplace_back().name = "head";
  return rig;
}

playback::IdleSpec idle_layer_spec(const rig::Rig& rig, double crossfade_s) {
  playback::IdleSpec spec;
  for (const rig::ChannelSpec& c : rig.channels)
    spec.limits.push_back({c.min, c.max, c.soft_margin, c.rest, c.max_velocity, c.max_acceleration, c.max_jerk});
  spec.noise.push_back({0, 10, 0.5, 2});  // the jaw too: idle moves it between shows
  spec.noise.push_back({1, 20, 0.3, 2});
  playback::BlinkSpec blinks;
  blinks.lids = {{2, 80, 0}};
  blinks.interval_min = 1;
  blinks.interval_max = 2;
  spec.blinks = blinks;
  spec.crossfade_s = crossfade_s;
  return spec;
}

playback::Show idle_layer_show(double duration) {
  playback::RawCurve raw;
  for (const auto& [t, v] : std::vector<std::pair<double, double>>{{0, 20}, {duration / 2, 25}, {duration, 20}}) {
    playback::RawKey k;
    k.time = t;
    k.value = v;
    raw.keys.push_back(k);
  }
  playback::Show show;
  show.name = "jaw";
  show.duration = duration;
  show.tracks.push_back({"jaw", raw, playback::Curve::build(raw), {}});
  return show;
}

/// Sets channel 0 to its value: a stand-in for any layer of the stack.
struct IdleLayerConstant final : LiveLayer {
  double value = 0;
  void apply(double, std::span<double> frame) noexcept override { frame[0] = value; }
};

TEST(LayerStack, TheTopLayerWinsAndEachSeesWhatIsBelow) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-100, 100);
  for (int k = 0; k < 100; ++k) {
    IdleLayerConstant low, high;
    low.value = any(rng);
    high.value = any(rng);
    LayerStack stack({&low, nullptr, &high});
    std::vector<double> frame{any(rng)};
    stack.apply(0, frame);
    ASSERT_EQ(frame[0], high.value);
  }
}

TEST(IdleLayer, ShowDrivesCoversTracksClipsAndTargets) {
  const rig::Rig rig = idle_layer_rig();
  const std::vector<char> drives = show_drives(rig, idle_layer_show(2));
  EXPECT_EQ(drives, (std::vector<char>{1, 0, 0}));
}

TEST(IdleLayer, HandOverToAndFromIdleIsEasedWithABoundedStepPerTick) {
  // Seeded families: random crossfades and hand-over times; the frame below is a moving "show".
  const rig::Rig rig = idle_layer_rig();
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    const double crossfade = std::uniform_real_distribution<double>(0.1, 1.5)(rng);
    const playback::IdleSpec spec = idle_layer_spec(rig, crossfade);
    IdleLayer idle(spec, seed, {0, 0, 0});
    playback::IdleGenerator reference(spec, seed);  // the same seed: the idle values themselves
    const double dt = 0.01;
    std::vector<double> below(3), frame(3), idle_values(3), previous_out(3), previous_below(3), previous_idle(3);
    for (int k = 0; k < 600; ++k) {
      const double t = k * dt;
      for (std::size_t c = 0; c < 3; ++c) below[c] = 10 * std::sin(0.7 * t + static_cast<double>(c)) + 5;
      frame = below;
      for (std::size_t c = 0; c < 3; ++c) idle_values[c] = spec.limits[c].rest;
      reference.sample(t, idle_values);
      idle.apply(t, frame);
      if (k == 0) {
        // At the start idle has no weight yet: what lies below passes unchanged.
        ASSERT_EQ(frame, below);
      } else {
        for (std::size_t c = 0; c < 3; ++c) {
          const double w = idle.weight(c);
          ASSERT_NEAR(frame[c], below[c] + w * (idle_values[c] - below[c]), 1e-9);
          // out = below + w (idle − below): its step is bounded by the parts' steps and the
          // smoothstep's slope (1.5/crossfade) times the gap.
          const double bound = std::abs(below[c] - previous_below[c]) + std::abs(idle_values[c] - previous_idle[c]) +
                               1.5 * dt / crossfade * std::abs(idle_values[c] - below[c]) + 1e-9;
          ASSERT_LE(std::abs(frame[c] - previous_out[c]), bound + 1.5 * dt / crossfade * 1e-9 + 1e-6) << "tick " << k;
        }
      }
      previous_out = frame;
      previous_below = below;
      previous_idle = idle_values;
    }
    EXPECT_DOUBLE_EQ(idle.weight(1), 1.0);
  }
}

struct IdleRun {
  std::vector<double> show_time, jaw_weight, pan_weight, lid_weight;
  std::vector<std::vector<double>> targets, commands;
};

IdleRun idle_controller_run(const rig::Rig& rig, const playback::Show& show, IdleLayer& idle, double lead_in, double lead_out) {
  testing::RecordingLink link;
  LayerStack stack({&idle});
  ControllerOptions options;
  options.tick_period_s = 0.02;
  options.stage_clock = nullptr;
  options.live = &stack;
  options.lead_in_s = lead_in;
  options.lead_out_s = lead_out;
  Controller controller(rig, show, {&link}, options);
  idle.watch(controller);
  controller.begin(0, rig.rest_frame());
  IdleRun run;
  for (int k = 0; controller.active() && k < 100000; ++k) {
    controller.tick(k * 0.02);
    if (controller.phase() != Phase::running) continue;
    run.show_time.push_back(controller.show_time());
    run.jaw_weight.push_back(idle.weight(0));
    run.pan_weight.push_back(idle.weight(1));
    run.lid_weight.push_back(idle.weight(2));
    run.targets.emplace_back(controller.target().begin(), controller.target().end());
    run.commands.emplace_back(controller.commanded().begin(), controller.commanded().end());
  }
  return run;
}

TEST(IdleLayer, TheShowWinsItsChannelsWhileItPlaysAndIdleTheRestAndTheTimeBetween) {
  const rig::Rig rig = idle_layer_rig();
  const playback::Show show = idle_layer_show(3);
  const double crossfade = 0.5;
  IdleLayer idle(idle_layer_spec(rig, crossfade), 5, show_drives(rig, show));
  const IdleRun run = idle_controller_run(rig, show, idle, 2, 2);
  ASSERT_GT(run.show_time.size(), 300u);
  EXPECT_NEAR(run.show_time.front(), -2, 0.03);
  EXPECT_NEAR(run.show_time.back(), 5, 0.03);
  playback::Sampler sampler(show, std::vector<std::string>{"jaw", "pan", "lid"}, rig.rest_frame());
  std::vector<double> frame(3);
  for (std::size_t k = 0; k < run.show_time.size(); ++k) {
    const double t = run.show_time[k];
    if (t >= 0 && t < show.duration) {
      // The show's channel is the show's alone.
      sampler.sample(t, frame);
      ASSERT_EQ(run.jaw_weight[k], 0.0) << t;
      ASSERT_DOUBLE_EQ(run.targets[k][0], frame[0]) << t;
    }
    if (t > -2 + crossfade + 0.03 && t < -crossfade) {
      ASSERT_EQ(run.jaw_weight[k], 1.0) << t;
    }
    if (t > show.duration + crossfade + 0.03) {
      ASSERT_EQ(run.jaw_weight[k], 1.0) << t;
    }
    if (t > -2 + crossfade + 0.03) {
      ASSERT_EQ(run.pan_weight[k], 1.0) << t;
    }
    // Hand-over both ways: idle's weight on the jaw moves by at most the smoothstep's slope.
    if (k > 0) {
      ASSERT_LE(std::abs(run.jaw_weight[k] - run.jaw_weight[k - 1]), 1.5 * 0.02 / crossfade + 1e-12) << t;
    }
    // Nothing leaves the channels' ranges.
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_GE(run.commands[k][c], rig.channels[c].min);
      ASSERT_LE(run.commands[k][c], rig.channels[c].max);
    }
  }
}

/// idle_layer_show with a behaviour layer (bound to the rig) blinking the lid the whole show.
playback::Show idle_layer_lively_show(const rig::Rig& rig, double duration) {
  playback::Show show = idle_layer_show(duration);
  playback::Layer layer;
  layer.name = "life";
  playback::LayerBehaviour b;
  b.seed = 3;
  b.to = duration;
  for (const rig::ChannelSpec& c : rig.channels) {
    b.channels.push_back(c.name);
    b.idle.limits.push_back({c.min, c.max, c.soft_margin, c.rest, c.max_velocity, c.max_acceleration, c.max_jerk});
  }
  playback::BlinkSpec blinks;
  blinks.lids = {{2, 80, 0}};
  blinks.interval_min = 0.8;
  blinks.interval_max = 1.2;
  b.idle.blinks = blinks;
  layer.behaviour = b;
  show.layers.push_back(layer);
  return show;
}

TEST(IdleLayer, ABehaviourLayersChannelsAreTheShowsWhileItPlaysAndIdlesAfter) {
  const rig::Rig rig = idle_layer_rig();
  const playback::Show show = idle_layer_lively_show(rig, 3);
  const std::vector<char> drives = show_drives(rig, show);
  EXPECT_EQ(drives, (std::vector<char>{1, 0, 1}));  // the jaw's track and the behaviour's lid
  const double crossfade = 0.5;
  IdleLayer idle(idle_layer_spec(rig, crossfade), 8, drives);
  const IdleRun run = idle_controller_run(rig, show, idle, 2, 2);
  playback::Sampler sampler(show, std::vector<std::string>{"jaw", "pan", "lid"}, rig.rest_frame());
  std::vector<double> frame(3);
  double lid_min = 100;
  int played = 0;
  for (std::size_t k = 0; k < run.show_time.size(); ++k) {
    const double t = run.show_time[k];
    if (t >= 0 && t < show.duration) {
      // The lid blinks as the show's behaviour says; idle has let go of it.
      sampler.sample(t, frame);
      ASSERT_EQ(run.lid_weight[k], 0.0) << t;
      ASSERT_DOUBLE_EQ(run.targets[k][2], frame[2]) << t;
      lid_min = std::min(lid_min, frame[2]);
      ++played;
    }
    if (t > -2 + crossfade + 0.03) {
      ASSERT_EQ(run.pan_weight[k], 1.0) << t;  // not the show's: idle's throughout
    }
    if (t > show.duration + crossfade + 0.03) {
      ASSERT_EQ(run.lid_weight[k], 1.0) << t;  // taken back after the show
    }
  }
  EXPECT_GT(played, 140);
  EXPECT_LT(lid_min, 10);  // the behaviour's blinks shut it
}

TEST(IdleLayer, TheShowsHandOversGoThroughIntermediateWeightsBothWays) {
  const rig::Rig rig = idle_layer_rig();
  const playback::Show show = idle_layer_show(3);
  IdleLayer idle(idle_layer_spec(rig, 0.5), 6, show_drives(rig, show));
  const IdleRun run = idle_controller_run(rig, show, idle, 2, 2);
  int fading_out = 0, fading_in = 0;
  for (std::size_t k = 0; k < run.show_time.size(); ++k) {
    const double w = run.jaw_weight[k];
    if (w > 0 && w < 1) (run.show_time[k] < 0 ? fading_out : fading_in) += run.show_time[k] > -1.4 ? 1 : 0;
  }
  EXPECT_GE(fading_out, 20);  // 0.5 s at 50 Hz, less a tick at each end
  EXPECT_GE(fading_in, 20);
}

TEST(IdleLayer, ApplyingIdleDoesNotAllocate) {
  const rig::Rig rig = idle_layer_rig();
  playback::IdleSpec spec = idle_layer_spec(rig, 0.3);
  spec.breathing = playback::BreathingSpec{{{1, 2}}, 4, 0.1};
  playback::GazeSpec gaze;
  gaze.eyes_pan = 0;
  gaze.head_pan = 1;
  spec.noise.clear();
  spec.gaze = gaze;
  IdleLayer idle(spec, 3, {1, 0, 0});
  std::vector<double> frame(3, 0.0);
  idle.apply(0, frame);
  const long before = testing::allocations.load();
  for (int k = 1; k < 3000; ++k) idle.apply(k * 0.01, frame);
  EXPECT_EQ(testing::allocations.load() - before, 0);
  EXPECT_GT(idle.generator().gaze()->saccades(), 5u);
}

TEST(IdleLayer, ThePuppeteerBeatsIdleAndTheEStopBeatsEverything) {
  const rig::Rig rig = idle_layer_rig();
  playback::Show show;
  show.name = "idle only";
  show.duration = 6;
  IdleLayer idle(idle_layer_spec(rig, 0.3), 9, show_drives(rig, show));
  LiveInputs puppet({{"jaw", 0, 30}, {"pan", -60, 60}, {"lid", 0, 100}}, {});

  testing::RecordingLink link;
  LayerStack stack({&idle, &puppet});
  ControllerOptions options;
  options.tick_period_s = 0.02;
  options.stage_clock = nullptr;
  options.live = &stack;
  Controller controller(rig, show, {&link}, options);
  idle.watch(controller);
  controller.begin(0, rig.rest_frame());
  int k = 0;
  double faulted_at = -1;
  for (; controller.active() && k < 10000; ++k) {
    const double now = k * 0.02;
    if (now >= 2 && now < 4) puppet.sink().post("channel/pan", -40, true, k);
    controller.tick(now);
    // The puppeteer's direct value wins over idle once its crossfade is over.
    if (now > 2 + kDirectCrossfadeS + 0.05 && now < 4) {
      ASSERT_DOUBLE_EQ(controller.target()[1], -40) << now;
    }
    if (now >= 4.5 && faulted_at < 0) {
      controller.fault(FaultCause::estop, 0, 0, now);
      faulted_at = now;
    }
  }
  ASSERT_GT(faulted_at, 0);
  EXPECT_EQ(controller.phase(), Phase::faulted);
  // The fail-safe (rest) is where every channel ended, whatever idle was doing.
  for (std::size_t c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(link.frames.back()[c], rig.channels[c].rest) << c;
}

}  // namespace
}  // namespace avar::control
