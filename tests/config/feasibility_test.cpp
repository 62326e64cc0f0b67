#include "avar/config/feasibility.hpp"

#include <gtest/gtest.h>

#include "../support/temp_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"

namespace avar::config {
namespace {

rig::Rig rig() {
  rig::Rig r;
  r.name = "r";
  for (const char* name : {"jaw", "pan"})
    r.channels.push_back({.name = name,
                          .unit = "deg",
                          .min = -30,
                          .max = 30,
                          .rest = 0,
                          .max_velocity = 10,
                          .max_acceleration = 100,
                          .max_jerk = 1000,
                          .ramp_velocity = 5,
                          .where = {}});
  return r;
}

playback::Track track(const std::string& channel, std::vector<playback::RawKey> keys) {
  playback::RawCurve raw{std::move(keys), {}};
  playback::Curve curve = playback::Curve::build(raw);
  return {channel, raw, std::move(curve), {}};
}

playback::RawKey key(double t, double v, playback::Interpolation i = playback::Interpolation::linear) {
  playback::RawKey k;
  k.time = t;
  k.value = v;
  k.interpolation = i;
  k.where = {"s.yaml", static_cast<int>(t) + 1, 7};
  return k;
}

playback::Show show() {
  playback::Show s;
  s.name = "s";
  s.duration = 6;
  // jaw: 0 -> 20 in 1 s (20 deg/s: twice too fast), then calm; pan: calm all along.
  s.tracks.push_back(track("jaw", {key(0, 0), key(1, 20), key(5, 0)}));
  s.tracks.push_back(track("pan", {key(0, 0), key(2, 5), key(3, 5, playback::Interpolation::step), key(4, 9)}));
  return s;
}

TEST(Feasibility, ReportsSegmentsThatAskTooMuchWithRequiredAndAllowed) {
  const auto found = check_feasibility(show(), rig());
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].kind, Infeasible::Kind::speed);
  EXPECT_EQ(found[0].channel, "jaw");
  EXPECT_NEAR(found[0].required, 20, 1e-6);
  EXPECT_DOUBLE_EQ(found[0].allowed, 10);
  EXPECT_EQ(found[0].to_string(), "s.yaml:1:7: jaw 0-1 s: speed 20 deg/s, allowed 10 deg/s");
  EXPECT_EQ(found[1].kind, Infeasible::Kind::jump);
  EXPECT_EQ(found[1].to_string(), "s.yaml:4:7: pan 3-4 s: jumps by 4 deg at once (step); the limiter shapes it");
}

TEST(Feasibility, SegmentDemandsGiveEachPlayedSegmentsShareOfTheLimits) {
  const std::vector<SegmentDemand> segments = segment_demands(show(), rig());
  ASSERT_EQ(segments.size(), 4u);  // jaw 0-1, 1-5; pan 0-2, 2-3 (the step 3-4 switches, it is not measured)
  EXPECT_NEAR(segments[0].usage(), 2.0, 1e-6);
  EXPECT_EQ(segments[0].to_string(), "s.yaml:1:7: jaw 0-1 s: speed 200 % of 10 deg/s, acceleration 0 % of 100 deg/s²");
  EXPECT_NEAR(segments[1].usage(), 0.5, 1e-6);
  EXPECT_NEAR(segments[2].usage(), 0.25, 1e-6);
  EXPECT_EQ(segments[3].channel, "pan");
  EXPECT_NEAR(segments[3].usage(), 0.0, 1e-9);
  // Leaving the range counts past 1, with how far.
  SegmentDemand outside = segments[1];
  outside.high = 36;  // 6 past the top of a 60-wide range
  EXPECT_NEAR(outside.usage(), 1.1, 1e-12);
}

TEST(Feasibility, BezierAccelerationIsMeasuredOnTheCurve) {
  playback::Show s;
  s.duration = 1;
  auto a = key(0, 0, playback::Interpolation::bezier);
  a.right = playback::Handle{0.3, 0};
  auto b = key(0.6, 20);
  b.left = playback::Handle{0.3, 20};
  s.tracks.push_back(track("jaw", {a, b}));
  const auto found = check_feasibility(s, rig());
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[1].kind, Infeasible::Kind::acceleration);
  // An S from 0 to 20 over 0.6 s with handles at the midpoint: the curve's own second
  // derivative peaks far above 100 deg/s² (about 6 * 20 / 0.6² = 333 at the ends).
  EXPECT_GT(found[1].required, 250);
  EXPECT_DOUBLE_EQ(found[1].allowed, 100);
}

TEST(Feasibility, RetimeStretchesJustEnoughAndKeepsTheRestOfTheTiming) {
  const playback::Show retimed = retime(show(), rig());
  EXPECT_TRUE(check_feasibility(retimed, rig()).size() == 1u);  // only the step jump is left
  const auto& jaw = retimed.tracks[0].raw.keys;
  const auto& pan = retimed.tracks[1].raw.keys;
  // The first second needs twice the time; everything after it moves by the added second.
  EXPECT_NEAR(jaw[1].time, 2.0, 1e-4);
  EXPECT_NEAR(jaw[2].time, 6.0, 1e-4);
  EXPECT_NEAR(retimed.duration, 7.0, 1e-4);
  // Tracks stay in step: pan's keys move with the same warp (its key at 2 s was 1 s past the
  // stretched span, so it lands at 3 s).
  EXPECT_NEAR(pan[1].time, 3.0, 1e-4);
  EXPECT_NEAR(pan[3].time, 5.0, 1e-4);
  EXPECT_DOUBLE_EQ(jaw[1].value, 20);
}

TEST(Feasibility, RetimeMovesCuesWithTheTimeAroundThem) {
  playback::Show s = show();
  for (double t : {0.5, 4.0}) {
    s.cues.emplace_back();
    s.cues.back().time = t;
    s.cues.back().osc_host = "127.0.0.1";
    s.cues.back().osc_port = 9000;
    s.cues.back().osc_address = "/cue";
  }
  const playback::Show retimed = retime(s, rig());
  ASSERT_EQ(retimed.cues.size(), 2u);
  EXPECT_NEAR(retimed.cues[0].time, 1.0, 1e-4);  // inside the stretched second: stretched with it
  EXPECT_NEAR(retimed.cues[1].time, 5.0, 1e-4);  // after it: later by the added second
}

TEST(Feasibility, RetimedShowWritesAndReadsBack) {
  const playback::Show retimed = retime(show(), rig());
  const std::string path = testing::temp_path("retimed.yaml");
  write_show_file(path, retimed, "written by avar check --retime");
  const playback::Show back = load_show_file(path);
  ASSERT_EQ(back.tracks.size(), 2u);
  EXPECT_NEAR(back.duration, retimed.duration, 1e-9);
  for (std::size_t t = 0; t < back.tracks.size(); ++t)
    for (double x = 0; x < back.duration; x += 0.05)
      EXPECT_NEAR(back.tracks[t].curve.evaluate(x), retimed.tracks[t].curve.evaluate(x), 1e-6);
}

}  // namespace
}  // namespace avar::config
