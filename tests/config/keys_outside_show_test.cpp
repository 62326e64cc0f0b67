// Keys before 0 or after a show's end (a Blender scene keyed from frame 0 exports its first key at
// a negative time): read, they shape the curve inside the show; the checks look only at what plays.
#include <gtest/gtest.h>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/feasibility.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"

namespace avar::config {
namespace {

// At 30 fps from frame 0 with the scene starting at frame 1: the first key is 1/30 s early. The
// last key (5 s) is past the show's end (4 s).
const char* const kOutsideShow = R"(name: keyed-from-frame-0
duration: 4
tracks:
  jaw:
    - {time: -0.0333333, value: 0}
    - {time: 1, value: 10}
    - {time: 5, value: 20}
  pan:
    - {time: -1, value: -20, interpolation: bezier, right: [-0.5, -20]}
    - {time: 1, value: 20, left: [0.5, 20]}
)";

// The jaw of kOutsideShow alone.
const char* const kOutsideJaw = R"(duration: 4
tracks:
  jaw:
    - {time: -0.0333333, value: 0}
    - {time: 1, value: 10}
    - {time: 5, value: 20}
)";

rig::Rig outside_rig(double min = -30, double max = 30, double max_velocity = 100) {
  rig::Rig r;
  r.name = "r";
  for (const char* name : {"jaw", "pan"})
    r.channels.push_back({.name = name,
                          .unit = "deg",
                          .min = min,
                          .max = max,
                          .rest = 0,
                          .max_velocity = max_velocity,
                          .max_acceleration = 1000,
                          .max_jerk = 10000,
                          .ramp_velocity = 10,
                          .where = {}});
  return r;
}

playback::Show outside_load(const std::string& text) { return load_show_file(testing::write_temp_file("show.yaml", text)); }

TEST(KeysOutsideShow, AreReadAndShapeTheCurveInsideTheShow) {
  const playback::Show show = outside_load(kOutsideShow);
  EXPECT_DOUBLE_EQ(show.duration, 4);
  ASSERT_EQ(show.tracks.size(), 2u);
  const playback::Curve& jaw = show.tracks[0].curve;
  EXPECT_DOUBLE_EQ(show.tracks[0].raw.keys[0].time, -0.0333333);
  // The value at 0 lies on the segment from the early key, not on the key itself.
  EXPECT_NEAR(jaw.evaluate(0), 10 * 0.0333333 / 1.0333333, 1e-12);
  EXPECT_GT(jaw.evaluate(0), 0);
  EXPECT_DOUBLE_EQ(jaw.evaluate(1), 10);
  // At the end, three quarters of the way to the key after it.
  EXPECT_DOUBLE_EQ(jaw.evaluate(4), 17.5);
  // The Bezier segment from -1 s crosses 0 mid-way in time: its value there is its middle value.
  EXPECT_NEAR(show.tracks[1].curve.evaluate(0), 0, 1e-9);
}

TEST(KeysOutsideShow, OrientationKeysAndTargetCurvesMayLieOutsideToo) {
  const playback::Show show = outside_load(R"(duration: 2
targets:
  gaze:
    x: [{time: -0.5, value: 0}, {time: 2.5, value: 1}]
    y: [{time: 0, value: 0}]
    z: [{time: 0, value: 0}]
    orientation_keys: {keys: [{time: -1, euler: [0, 0, 0]}, {time: 3, euler: [0, 0, 1]}]}
)");
  ASSERT_EQ(show.targets.size(), 1u);
  EXPECT_NEAR(show.targets[0].xyz[0].evaluate(0), 1.0 / 6, 1e-12);
}

TEST(KeysOutsideShow, ClipKeysStillLieWithinTheirClip) {
  // A clip is placed, stretched and looped by its own span: its keys must stay inside it.
  EXPECT_EQ(avar::testing::load_error(load_show_file, R"(duration: 4
clips:
  wave: {duration: 2, tracks: {jaw: [{time: -1, value: 0}]}}
layers: [{name: base, clips: [{clip: wave, start: 0}]}]
)",
                                      "show.yaml"),
            ":3:45: key time -1 s of track 'jaw' is outside clip 'wave', which runs from 0 to 2 s");
}

TEST(KeysOutsideShow, CheckIgnoresValuesThatNeverPlayButNotTheCurveThatDoes) {
  // The jaw's early key is at 0 and its late key at 20, outside [0.3, 18]: neither plays; the
  // curve inside does (0.32 at the start, 17.5 at the end), so the show checks clean.
  const ShowCheck fine = check_show_against_rig(outside_load(kOutsideJaw), outside_rig(0.3, 18));
  EXPECT_TRUE(fine.errors.empty()) << fine.errors[0].to_string();
  // With the limit at 17 the end of the show (17.5) is outside: named at the key after the end.
  const ShowCheck late = check_show_against_rig(outside_load(kOutsideJaw), outside_rig(-30, 17));
  ASSERT_EQ(late.errors.size(), 1u);
  EXPECT_NE(late.errors[0].to_string().find(":6:7: the curve of 'jaw' is at 17.5 at the show's end (4 s), shaped by the key "
                                            "at 5 s outside the show; expected it within the channel's limits [-30, 17] deg"),
            std::string::npos)
      << late.errors[0].to_string();
  // A start outside the limits: named at the last key before 0.
  const ShowCheck early = check_show_against_rig(outside_load(kOutsideJaw), outside_rig(1, 30));
  ASSERT_EQ(early.errors.size(), 1u);
  EXPECT_NE(early.errors[0].to_string().find(":4:7: the curve of 'jaw' is at 0.32"), std::string::npos)
      << early.errors[0].to_string();
}

TEST(KeysOutsideShow, FeasibilityMeasuresOnlyThePlayedPartOfEachSegment) {
  // Before 0, the jaw jumps 100 deg in 0.1 s (1000 deg/s); after the end, likewise. Neither plays.
  const playback::Show show = outside_load(R"(duration: 2
tracks:
  jaw:
    - {time: -1.1, value: -100}
    - {time: -1, value: 0}
    - {time: 1, value: 10}
    - {time: 3, value: 10}
    - {time: 3.1, value: 110}
    - {time: 4, value: 0, interpolation: step}
    - {time: 5, value: 50}
)");
  EXPECT_TRUE(check_feasibility(show, outside_rig(-200, 200, 20)).empty());
  // A segment that crosses 0 is measured on its played part: 5 deg/s, reported from 0 s.
  const auto slow = check_feasibility(show, outside_rig(-200, 200, 4));
  ASSERT_EQ(slow.size(), 1u);
  EXPECT_DOUBLE_EQ(slow[0].t0, 0);
  EXPECT_DOUBLE_EQ(slow[0].t1, 1);
  EXPECT_NEAR(slow[0].required, 5, 1e-6);
}

TEST(KeysOutsideShow, RetimeStretchesThePlayedPartAndKeepsTimeZero) {
  const playback::Show show = outside_load(R"(duration: 2
tracks:
  jaw: [{time: -1, value: 0}, {time: 1, value: 10}, {time: 2, value: 10}]
)");
  const playback::Show slowed = retime(show, outside_rig(-200, 200, 2.5));
  const auto& keys = slowed.tracks[0].raw.keys;
  // -1 to 1 s at 5 deg/s, stretched twice about time 0: the show still starts mid-segment.
  EXPECT_NEAR(keys[0].time, -2, 1e-3);
  EXPECT_NEAR(keys[1].time, 2, 1e-3);
  EXPECT_TRUE(check_feasibility(slowed, outside_rig(-200, 200, 2.5)).empty());
  EXPECT_NEAR(slowed.tracks[0].curve.evaluate(0), show.tracks[0].curve.evaluate(0), 1e-12);
}

}  // namespace
}  // namespace avar::config
