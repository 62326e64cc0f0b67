// A written show reads back to the same curves: every interpolation, handle type, easing
// parameter, extrapolation and Cycles setting of Blender's golden set, and targets.
#include "avar/config/show_writer.hpp"

#include <gtest/gtest.h>

#include "../support/temp_file.hpp"
#include "avar/config/show_file.hpp"

namespace avar::config {
namespace {

void expect_same_curve(const playback::Curve& a, const playback::Curve& b, const std::string& what) {
  for (double t = -3; t <= 13; t += 0.0173) ASSERT_EQ(a.evaluate(t), b.evaluate(t)) << what << " at " << t;
}

void round_trip(const std::string& path) {
  const playback::Show original = load_show_file(path);
  const std::string copy = avar::testing::temp_path("copy.yaml");
  write_show_file(copy, original, "round trip");
  const playback::Show again = load_show_file(copy);
  EXPECT_EQ(again.name, original.name);
  EXPECT_EQ(again.duration, original.duration);
  EXPECT_EQ(again.loop, original.loop);
  ASSERT_EQ(again.tracks.size(), original.tracks.size());
  for (std::size_t i = 0; i < original.tracks.size(); ++i) {
    EXPECT_EQ(again.tracks[i].channel, original.tracks[i].channel);
    expect_same_curve(original.tracks[i].curve, again.tracks[i].curve, original.tracks[i].channel);
  }
  ASSERT_EQ(again.targets.size(), original.targets.size());
  for (std::size_t i = 0; i < original.targets.size(); ++i) {
    EXPECT_EQ(again.targets[i].kind, original.targets[i].kind);
    EXPECT_EQ(again.targets[i].aim_axis, original.targets[i].aim_axis);
    for (std::size_t a = 0; a < 3 && original.targets[i].has_point(); ++a)
      expect_same_curve(original.targets[i].xyz[a], again.targets[i].xyz[a], original.targets[i].effector);
    for (std::size_t a = 0; a < 3 && original.targets[i].has_orientation(); ++a)
      expect_same_curve(original.targets[i].rpy[a], again.targets[i].rpy[a], original.targets[i].effector);
  }
}

TEST(ShowWriter, EveryCurveFieldOfBlendersGoldenSetSurvivesARoundTrip) {
  round_trip(AVAR_SOURCE_DIR "/tests/playback/golden/blender_curves.yaml");
}

TEST(ShowWriter, ExamplesWithTargetsAndAvarSplinesSurviveARoundTrip) {
  round_trip(AVAR_SOURCE_DIR "/examples/shows/look-around.yaml");
  round_trip(AVAR_SOURCE_DIR "/examples/shows/curves-tour.yaml");
  round_trip(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  round_trip(AVAR_SOURCE_DIR "/examples/shows/figure-eight.yaml");
}

TEST(ShowWriter, OscCuesSurviveARoundTripAndDigitalCuesPlayAsTheirTracks) {
  const std::string path = AVAR_SOURCE_DIR "/examples/shows/stage-lights.yaml";
  round_trip(path);
  const playback::Show original = load_show_file(path);
  const playback::Show again = load_show_text(show_text(original, "cues"), "again.yaml");
  std::vector<const playback::Cue*> osc;
  for (const playback::Cue& c : original.cues)
    if (c.is_osc()) osc.push_back(&c);
  ASSERT_EQ(osc.size(), 2u);
  ASSERT_EQ(again.cues.size(), osc.size());
  for (std::size_t i = 0; i < osc.size(); ++i) {
    EXPECT_EQ(again.cues[i].time, osc[i]->time);
    EXPECT_EQ(again.cues[i].osc_host, osc[i]->osc_host);
    EXPECT_EQ(again.cues[i].osc_port, osc[i]->osc_port);
    EXPECT_EQ(again.cues[i].osc_address, osc[i]->osc_address);
    ASSERT_EQ(again.cues[i].osc_arguments.size(), osc[i]->osc_arguments.size());
    for (std::size_t a = 0; a < osc[i]->osc_arguments.size(); ++a) {
      EXPECT_EQ(again.cues[i].osc_arguments[a].type, osc[i]->osc_arguments[a].type) << "cue " << i << " argument " << a;
      EXPECT_EQ(again.cues[i].osc_arguments[a].number, osc[i]->osc_arguments[a].number);
      EXPECT_EQ(again.cues[i].osc_arguments[a].text, osc[i]->osc_arguments[a].text);
    }
  }
  // A float that is a whole number stays a float; a string stays a string.
  playback::Show typed = original;
  typed.cues = {*osc[0]};
  typed.cues[0].osc_arguments = {{'f', 2, ""}, {'i', -7, ""}, {'s', 0, "go now"}};
  const playback::Show typed_again = load_show_text(show_text(typed, "typed"), "typed.yaml");
  ASSERT_EQ(typed_again.cues.size(), 1u);
  ASSERT_EQ(typed_again.cues[0].osc_arguments.size(), 3u);
  EXPECT_EQ(typed_again.cues[0].osc_arguments[0].type, 'f');
  EXPECT_EQ(typed_again.cues[0].osc_arguments[0].number, 2);
  EXPECT_EQ(typed_again.cues[0].osc_arguments[1].type, 'i');
  EXPECT_EQ(typed_again.cues[0].osc_arguments[2].text, "go now");
}

TEST(ShowWriter, OrientationAndPoseTargetsSurviveARoundTrip) {
  round_trip(avar::testing::write_temp_file("pose.yaml", R"(duration: 2
targets:
  hand:
    point: [0.3, 0.1, 0.2]
    roll: [{time: 0, value: 0}, {time: 2, value: 1, interpolation: bezier, left_type: auto_clamped}]
    pitch: [{time: 0, value: 0.5}]
    yaw: [{time: 0, value: -0.5}]
  wrist: {orientation: [0, 1.5, 0]}
)"));
}

TEST(ShowWriter, AnUnwritablePathIsNamed) {
  const playback::Show show = load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  try {
    write_show_file("/nonexistent/dir/show.yaml", show, "x");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/show.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::config
