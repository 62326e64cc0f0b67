// The timecode chase against a scripted source on the stepped clock: lock, filtering of arrival
// jitter, a source running fast, jumps, dropouts (freewheel, then a safe stop), and a figure
// that never exceeds its limits whatever the source does.
#include "avar/control/chase_clock.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "avar/control/controller.hpp"
#include "../support/recording_link.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

/// A stepped source: a frame's position arrives at each frame boundary of the source's time
/// (loop time -> source seconds by `source_at`), late by a seeded jitter, except while `silent`.
class ScriptedTimecode final : public inputs::TimecodeSource {
 public:
  ScriptedTimecode(std::function<double(double)> source_at, double jitter_s, FrameRate rate = FrameRate::fps25)
      : source_at_(std::move(source_at)), jitter_s_(jitter_s), rate_(rate), rng_(4242) {}
  std::function<bool(double)> silent = [](double) { return false; };
  void start() override {}
  void stop() noexcept override {}
  inputs::TimecodeReading latest() const noexcept override { return mailbox_.read(); }
  inputs::TimecodeCounters counters() const noexcept override { return {}; }
  std::string describe() const override { return "scripted"; }
  bool stepped() const noexcept override { return true; }
  void advance_to(std::int64_t now_ns) noexcept override {
    const double now = static_cast<double>(now_ns) * 1e-9;
    const double period = 1.0 / 25.0;  // the sender's frame clock
    std::uniform_real_distribution<double> late(0.0, jitter_s_);
    while (next_send_ <= now) {
      const double sent = next_send_;
      next_send_ += period;
      if (silent(sent)) continue;
      const double position = source_at_(sent);
      const double frames = position * frames_per_second(rate_);
      const auto whole = static_cast<std::int64_t>(std::floor(frames));
      inputs::TimecodeFix fix{from_frame_number(whole, rate_), frames - static_cast<double>(whole), false};
      // Arrives late by the jitter; the position named is that of when it was sent (the
      // receiver does not know the lateness).
      const double arrival = sent + late(rng_);
      mailbox_.publish(fix, static_cast<std::int64_t>(std::llround(arrival * 1e9)));
    }
  }

 private:
  std::function<double(double)> source_at_;
  double jitter_s_;
  FrameRate rate_;
  std::mt19937_64 rng_;
  double next_send_ = 0;
  inputs::TimecodeMailbox mailbox_;
};

constexpr double kChaseDt = 0.01;

TEST(ChaseClockStepped, LocksAndFiltersArrivalJitter) {
  std::printf("seed 4242\n");
  ScriptedTimecode source([](double t) { return 3600.0 + t; }, 0.001);
  ChaseOptions o;
  o.offset_s = 3600.0;
  ChaseClock chase(source, o, nullptr);
  EXPECT_EQ(chase.state(), ChaseState::waiting);
  for (int k = 0; k < 1000; ++k) {
    const ShowClockReading r = chase.read(k * kChaseDt);
    ASSERT_FALSE(r.stop);
    if (k > 100) {
      ASSERT_EQ(chase.state(), ChaseState::locked);
      // Show time follows the source within the jitter, filtered.
      ASSERT_NEAR(r.show_time_s, k * kChaseDt, 0.0015) << k;
    }
  }
  EXPECT_LT(chase.errors().percentile_ns(0.99), 2'000'000);
  EXPECT_EQ(chase.jumps(), 0U);
}

TEST(ChaseClockStepped, FollowsASourceRunningFast) {
  // The source's clock runs 0.5% fast: the filtered rate follows, the error stays small.
  ScriptedTimecode source([](double t) { return 10.0 + 1.005 * t; }, 0.0);
  ChaseClock chase(source, ChaseOptions{}, nullptr);
  for (int k = 0; k < 1500; ++k) (void)chase.read(k * kChaseDt);
  EXPECT_NEAR(chase.rate(), 1.005, 5e-4);
  EXPECT_LT(std::abs(chase.last_error_s()), 0.001);
  EXPECT_EQ(chase.jumps(), 0U);
}

TEST(ChaseClockStepped, JumpsWhenTheSourceJumpsAndWaitsBeforeTheOffset) {
  ScriptedTimecode source([](double t) { return t < 2.0 ? 5.0 + t : 60.0 + t; }, 0.0);
  ChaseOptions o;
  o.offset_s = 6.0;  // show time 0 at source 00:00:06:00
  ChaseClock chase(source, o, nullptr);
  double before_jump = 0, after_jump = 0;
  for (int k = 0; k < 300; ++k) {
    const double t = k * kChaseDt;
    const ShowClockReading r = chase.read(t);
    if (t < 0.9) {
      ASSERT_DOUBLE_EQ(r.show_time_s, 0.0) << "before the offset the show holds its first frame";
    }
    if (k == 195) before_jump = r.show_time_s;
    if (k == 215) after_jump = r.show_time_s;
  }
  EXPECT_NEAR(before_jump, 5.0 + 1.95 - 6.0, 0.002);
  EXPECT_NEAR(after_jump, 60.0 + 2.15 - 6.0, 0.002);
  EXPECT_EQ(chase.jumps(), 1U);
}

TEST(ChaseClockStepped, FreewheelsThroughADropoutThenStopsWhenTheSourceStops) {
  ScriptedTimecode source([](double t) { return t; }, 0.0);
  // Silent 1.0-1.5 s (shorter than the freewheel), then gone from 3.0 s.
  source.silent = [](double t) { return (t >= 1.0 && t < 1.5) || t >= 3.0; };
  ChaseOptions o;
  o.freewheel_s = 1.0;
  ChaseClock chase(source, o, nullptr);
  bool freewheeled = false;
  double stopped_at = -1;
  for (int k = 0; k < 600 && stopped_at < 0; ++k) {
    const double t = k * kChaseDt;
    const ShowClockReading r = chase.read(t);
    if (chase.state() == ChaseState::freewheeling && t < 1.6) {
      freewheeled = true;
      ASSERT_NEAR(r.show_time_s, t, 1e-6) << "freewheeling keeps the pace";
    }
    if (r.stop) stopped_at = t;
  }
  EXPECT_TRUE(freewheeled);
  // The last position arrived at 2.96 s; the run stops once 1 s has passed without one.
  EXPECT_NEAR(stopped_at, 3.97, 0.011);
  EXPECT_EQ(chase.state(), ChaseState::stopped);
  EXPECT_TRUE(chase.read(10.0).stop) << "stopped stays stopped";
}

TEST(ChaseClockStepped, RepeatedFramesArePausedNotNew) {
  ScriptedTimecode source([](double t) { return t < 1.0 ? t : 1.0; }, 0.0);  // the sender pauses at 1 s
  ChaseOptions o;
  o.freewheel_s = 0.5;
  ChaseClock chase(source, o, nullptr);
  double stopped_at = -1;
  for (int k = 0; k < 300 && stopped_at < 0; ++k)
    if (chase.read(k * kChaseDt).stop) stopped_at = k * kChaseDt;
  EXPECT_NEAR(stopped_at, 1.5, 0.05);
}

Rig chase_rig() {
  Rig rig;
  rig.name = "chase";
  rig.channels.push_back({.name = "jaw",
                          .unit = "deg",
                          .min = 0,
                          .max = 30,
                          .rest = 0,
                          .max_velocity = 100,
                          .max_acceleration = 800,
                          .max_jerk = 8000,
                          .ramp_velocity = 20,
                          .where = {}});
  rig.links.emplace_back().name = "head";
  return rig;
}

playback::Show chase_show() {
  playback::RawCurve raw;
  for (int i = 0; i <= 20; ++i) {
    playback::RawKey k;
    k.time = i;
    k.value = (i % 2 == 0) ? 2.0 : 28.0;
    raw.keys.push_back(k);
  }
  playback::Show show;
  show.name = "saw";
  show.duration = 20.0;
  show.tracks.push_back(playback::Track{"jaw", raw, playback::Curve::build(raw), {}});
  return show;
}

TEST(ChaseClockStepped, JumpsAndLossMoveTheFigureWithinItsLimitsThenEaseToRest) {
  const Rig rig = chase_rig();
  const playback::Show show = chase_show();
  // Forward to 3 s, jumps to 12.5 s, back to 1.25 s, then the source is lost at 6 s.
  ScriptedTimecode source([](double t) { return t < 3.0 ? t : (t < 4.5 ? t + 9.5 : t - 3.25); }, 0.0005);
  source.silent = [](double t) { return t >= 6.0; };
  ChaseOptions o;
  o.freewheel_s = 0.5;
  ChaseClock chase(source, o, nullptr);
  testing::RecordingLink link;
  ControllerOptions co;
  co.tick_period_s = kChaseDt;
  co.stage_clock = nullptr;
  co.show_clock = &chase;
  Controller c(rig, show, {&link}, co);
  c.begin(0.0, rig.rest_frame());
  int k = 0;
  for (; c.active() && k < 2000; ++k) c.tick(k * kChaseDt);
  EXPECT_EQ(chase.jumps(), 2U);
  EXPECT_EQ(chase.state(), ChaseState::stopped);
  EXPECT_EQ(c.phase(), Phase::disabled) << "eased to rest and finished";
  EXPECT_LT(k, 900) << "stopped soon after the source was lost";
  ASSERT_GT(link.frames.size(), 3U);
  EXPECT_DOUBLE_EQ(link.frames.back()[0], rig.channels[0].rest);
  // Never a snap: speed and acceleration within the channel's limits on every tick.
  const auto& ch = rig.channels[0];
  double v_prev = 0;
  for (std::size_t i = 1; i < link.frames.size(); ++i) {
    const double v = (link.frames[i][0] - link.frames[i - 1][0]) / kChaseDt;
    ASSERT_LE(std::abs(v), ch.max_velocity * (1 + 1e-9)) << i;
    ASSERT_LE(std::abs(v - v_prev) / kChaseDt, ch.max_acceleration * 1.001 + 1e-6) << i;
    ASSERT_GE(link.frames[i][0], ch.min);
    ASSERT_LE(link.frames[i][0], ch.max);
    v_prev = v;
  }
}

}  // namespace
}  // namespace avar::control
