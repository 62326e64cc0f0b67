#include "avar/config/show_check.hpp"

#include <gtest/gtest.h>

namespace avar::config {
namespace {

rig::Rig check_rig() {
  rig::Rig r;
  r.name = "r";
  r.channels.push_back({.name = "jaw", .unit = "deg", .min = 0, .max = 30, .rest = 0, .max_velocity = 100, .max_acceleration = 1000, .max_jerk = 10000, .ramp_velocity = 10, .where = {}});
  r.channels.push_back({.name = "pan", .unit = "deg", .min = -60, .max = 60, .rest = 0, .max_velocity = 100, .max_acceleration = 1000, .max_jerk = 10000, .ramp_velocity = 10, .where = {}});
  return r;
}

playback::Track check_track(const std::string& channel, std::vector<playback::RawKey> keys) {
  playback::RawCurve raw{std::move(keys), {"s.yaml", 3, 3}};
  playback::Curve curve = playback::Curve::build(raw);
  return {channel, raw, std::move(curve), {"s.yaml", 3, 3}};
}

playback::RawKey check_key(double t, double v, int line) {
  playback::RawKey k;
  k.time = t;
  k.value = v;
  k.where = {"s.yaml", line, 7};
  return k;
}

TEST(ShowCheck, ValuesOutsideLimitsAreErrorsAtTheKey) {
  playback::Show show;
  show.duration = 2;
  show.where = {"s.yaml", 1, 1};
  show.tracks.push_back(check_track("jaw", {check_key(0, 0, 4), check_key(1, 31, 5), check_key(2, -1, 6)}));
  const ShowCheck check = check_show_against_rig(show, check_rig());
  ASSERT_EQ(check.errors.size(), 2u);
  EXPECT_EQ(check.errors[0].to_string(), "s.yaml:5:7: value 31 at 1 s is outside channel 'jaw' limits [0, 30] deg");
  EXPECT_EQ(check.errors[1].where.line, 6);
  EXPECT_FALSE(check.ok());
}

TEST(ShowCheck, UnknownChannelIsAnErrorListingTheRigsChannels) {
  playback::Show show;
  show.duration = 1;
  show.tracks.push_back(check_track("chin", {check_key(0, 0, 4)}));
  const ShowCheck check = check_show_against_rig(show, check_rig());
  ASSERT_EQ(check.errors.size(), 1u);
  EXPECT_EQ(check.errors[0].message, "unknown channel 'chin'; expected one of the rig 'r' channels: jaw, pan");
}

TEST(ShowCheck, BezierOvershootAndUndrivenChannelsAreWarnings) {
  playback::Show show;
  show.duration = 2;
  auto a = check_key(0, 0, 4);
  a.interpolation = playback::Interpolation::bezier;
  a.right = playback::Handle{0.5, 60};  // pulls the curve far above 30
  auto b = check_key(1, 30, 5);
  b.left = playback::Handle{0.5, 60};
  show.tracks.push_back(check_track("jaw", {a, b}));
  const ShowCheck check = check_show_against_rig(show, check_rig());
  EXPECT_TRUE(check.ok());
  ASSERT_EQ(check.warnings.size(), 2u);
  EXPECT_NE(check.warnings[0].message.find("between 0 s and 1 s reaches"), std::string::npos) << check.warnings[0].message;
  EXPECT_NE(check.warnings[0].message.find("it will be clamped"), std::string::npos);
  EXPECT_EQ(check.warnings[1].message, "no track drives channel 'pan'; it holds its rest pose 0");
}

}  // namespace
}  // namespace avar::config
