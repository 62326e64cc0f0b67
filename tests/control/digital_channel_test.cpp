// Digital channels (relays, valves, LEDs) switch, they do not move: the limiter passes 0 or 1
// on the tick the target crosses the middle, never anything between; soft start, soft stop and
// the fail-safe switch them at once while the analog channels beside them ease as before.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/limiter.hpp"
#include "avar/control/ramp.hpp"
#include "../support/recording_link.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

constexpr double kDigitalInf = std::numeric_limits<double>::infinity();

ChannelLimits digital_limits() { return {0, 1, kDigitalInf, kDigitalInf, kDigitalInf, 0, true}; }

TEST(DigitalLimiter, PassesZeroOrOneOnTheTickTheTargetCrossesTheMiddle) {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    Limiter limiter({digital_limits(), {-10, 10, 50, 500, 5000, 0}}, 0.02);
    std::uniform_real_distribution<double> any(-0.5, 1.5), analog(-10, 10);
    std::vector<double> out(2);
    double last_analog = 0;
    for (int k = 0; k < 500; ++k) {
      const double target = any(rng);
      ASSERT_EQ(limiter.apply(std::vector<double>{target, analog(rng)}, out), Status::ok);
      EXPECT_EQ(out[0], target >= 0.5 ? 1.0 : 0.0) << "tick " << k << " target " << target;
      // The analog channel beside it keeps its speed limit.
      EXPECT_LE(std::abs(out[1] - last_analog), 50 * 0.02 * (1 + 1e-9) + 1e-12);
      last_analog = out[1];
    }
  }
}

TEST(DigitalLimiter, AStepKeySwitchesOnItsTickAndHoldsWithoutIntermediateValues) {
  Limiter limiter({digital_limits()}, 0.02);
  std::vector<double> out(1);
  for (int k = 0; k < 100; ++k) {
    const double t = k * 0.02;
    const double target = t >= 0.5 && t < 1.2 ? 1.0 : 0.0;  // step keys at 0.5 s and 1.2 s
    ASSERT_EQ(limiter.apply(std::vector<double>{target}, out), Status::ok);
    EXPECT_EQ(out[0], target) << t;
    EXPECT_TRUE(limiter.settled());
    EXPECT_EQ(limiter.max_lag(0), 0.0);
  }
}

TEST(DigitalLimiter, KeepsItsGoalOnNonFiniteTargetsAndSnapsResetsNeedingNoGlide) {
  Limiter limiter({digital_limits(), {0, 30, 100, 1000, 20000, 0}}, 0.02);
  limiter.reset(std::vector<double>{0.8, 0});
  EXPECT_EQ(limiter.last()[0], 1.0);
  std::vector<double> out(2);
  EXPECT_EQ(limiter.apply(std::vector<double>{std::nan(""), 0}, out), Status::not_finite);
  EXPECT_EQ(out[0], 1.0);
  EXPECT_EQ(limiter.apply(std::vector<double>{2.0, 0}, out), Status::ok);
  EXPECT_EQ(limiter.clamped(0), 1u);  // 2 is outside [0, 1]: counted, switched on
  // A soft start that only switches takes the shortest time; the analog channel sets it otherwise.
  EXPECT_DOUBLE_EQ(limiter.glide_duration(std::vector<double>{0.0, 0.0}, std::vector<double>{0, 0}, 0.25), 0.25);
  limiter.glide_to(std::vector<double>{0.0, 0.0}, 0.25);
  EXPECT_FALSE(limiter.gliding(0));
  EXPECT_EQ(limiter.apply(std::vector<double>{0.0, 0}, out), Status::ok);
  EXPECT_EQ(out[0], 0.0);
}

TEST(DigitalRamp, SwitchedChannelsAreOnTheirGoalFromTheStartAndSetNoDuration) {
  Ramp ramp(2, {1, 0});
  ramp.plan(std::vector<double>{1, 0}, std::vector<double>{0, 10}, std::vector<double>{0.001, 10}, 0.1);
  EXPECT_NEAR(ramp.duration(), 3.14159265358979 * 10 / 20, 1e-12);  // the analog channel's alone
  std::vector<double> out(2);
  ramp.sample(0.0, out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_EQ(out[1], 0.0);
  ramp.sample(0.5 * ramp.duration(), out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_NEAR(out[1], 5.0, 1e-12);
}

Rig relay_and_jaw_rig() {
  Rig rig;
  rig.name = "prop";
  ChannelSpec relay{.name = "relay",
                    .unit = "",
                    .kind = rig::ChannelKind::digital,
                    .min = 0,
                    .max = 1,
                    .rest = 0,
                    .max_velocity = kDigitalInf,
                    .max_acceleration = kDigitalInf,
                    .max_jerk = kDigitalInf,
                    .ramp_velocity = kDigitalInf,
                    .where = {}};
  rig.channels.push_back(relay);
  rig.channels.push_back({.name = "jaw",
                          .unit = "deg",
                          .min = 0,
                          .max = 30,
                          .rest = 0,
                          .max_velocity = 200,
                          .max_acceleration = 2000,
                          .max_jerk = 20000,
                          .ramp_velocity = 20,
                          .where = {}});
  rig.links.emplace_back().name = "props";
  for (std::size_t c = 0; c < 2; ++c) {
    ActuatorSpec a;
    a.channel = rig::ChannelIndex{c};
    a.link = rig::LinkIndex{0};
    a.failsafe = Failsafe::rest;
    rig.actuators.push_back(a);
  }
  return rig;
}

playback::Track digital_track(const std::string& channel, std::vector<std::pair<double, double>> keys,
                              playback::Interpolation interpolation) {
  playback::RawCurve raw;
  for (auto [t, v] : keys) {
    playback::RawKey k;
    k.time = t;
    k.value = v;
    k.interpolation = interpolation;
    raw.keys.push_back(k);
  }
  playback::Curve curve = playback::Curve::build(raw);
  return playback::Track{channel, raw, std::move(curve), {}};
}

/// The relay on from the start, off at 1 s, on again at 1.5 s to the end (3 s); the jaw opens.
playback::Show relay_show() {
  playback::Show show;
  show.name = "relay";
  show.duration = 3.0;
  show.tracks.push_back(digital_track("relay", {{0.0, 1.0}, {1.0, 0.0}, {1.5, 1.0}, {3.0, 1.0}}, playback::Interpolation::step));
  show.tracks.push_back(digital_track("jaw", {{0.0, 0.0}, {1.5, 20.0}, {3.0, 0.0}}, playback::Interpolation::linear));
  return show;
}

TEST(DigitalController, SwitchesAtOnceInSoftStartOnStepKeysAndInSoftStop) {
  const Rig rig = relay_and_jaw_rig();
  const playback::Show show = relay_show();
  testing::RecordingLink link;
  const double dt = 0.01;
  Controller c(rig, show, {&link}, {.tick_period_s = dt});
  c.begin(0.0, rig.rest_frame());
  std::vector<double> times;
  std::vector<Phase> phases;
  for (int k = 0; c.active() && k < 100000; ++k) {
    c.tick(k * dt);
    times.push_back(k * dt);
    phases.push_back(c.phase());
  }
  ASSERT_GT(link.frames.size(), 300u);
  EXPECT_EQ(link.frames.front()[0], 1.0);  // the soft start switches to the show's first value at once
  const double start = c.show_start_time();
  ASSERT_GT(start, 0.0);
  bool stopped_off = false;
  for (std::size_t k = 0; k < link.frames.size(); ++k) {
    const double relay = link.frames[k][0];
    ASSERT_TRUE(relay == 0.0 || relay == 1.0) << relay;
    if (phases[k] == Phase::running) {
      const double show_t = times[k] - start;
      EXPECT_EQ(relay, show_t >= 1.0 && show_t < 1.5 ? 0.0 : 1.0) << "show time " << show_t;
    }
    if (phases[k] == Phase::stopping && !stopped_off) {
      EXPECT_EQ(relay, 0.0) << "the soft stop's first tick switches to rest";
      stopped_off = true;
    }
  }
  EXPECT_TRUE(stopped_off);
  EXPECT_EQ(link.frames.back()[0], 0.0);
  EXPECT_DOUBLE_EQ(link.frames.back()[1], 0.0);
}

TEST(DigitalController, AFaultSwitchesToRestOnItsTickWhileTheJawEases) {
  const Rig rig = relay_and_jaw_rig();
  const playback::Show show = relay_show();
  testing::RecordingLink link;
  const double dt = 0.01;
  Controller c(rig, show, {&link}, {.tick_period_s = dt});
  c.begin(0.0, rig.rest_frame());
  int k = 0;
  for (; c.active() && (c.phase() != Phase::running || c.show_time() < 2.0); ++k) c.tick(k * dt);
  ASSERT_EQ(link.frames.back()[0], 1.0);
  const double jaw_before = link.frames.back()[1];
  ASSERT_GT(jaw_before, 5.0);
  c.fault(FaultCause::estop, 0, 0, k * dt);
  c.tick(k * dt);
  ++k;
  EXPECT_EQ(link.frames.back()[0], 0.0);               // off on the fault's own tick
  EXPECT_GT(link.frames.back()[1], 0.9 * jaw_before);  // the jaw eases, it does not snap
  for (; c.active(); ++k) c.tick(k * dt);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::estop);
  EXPECT_EQ(link.frames.back()[0], 0.0);
  EXPECT_DOUBLE_EQ(link.frames.back()[1], 0.0);
}

}  // namespace
}  // namespace avar::control
