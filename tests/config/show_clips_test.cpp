// Clips and layers in show files: loading, whole-file validation with file:line:column, the
// writer's exact round trip, the check against a rig (unknown channels in clips and masks), and
// the feasibility of the composed motion.
#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/feasibility.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"

namespace avar::config {
namespace {

using avar::testing::replace;

const std::string kExample = AVAR_SOURCE_DIR "/examples/shows/layered-head.yaml";
const std::string kClipsRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

std::string clips_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }

const std::string kClipsShow = R"(duration: 10
clips:
  idle: {duration: 4, mode: loop, tracks: {neck_pan: [{time: 0, value: -5}, {time: 2, value: 5}, {time: 4, value: -5}]}}
  wave:
    duration: 3
    mode: hold
    tracks:
      jaw: [{time: 0, value: 0}, {time: 3, value: 20}]
layers:
  - {name: base, clips: [{clip: idle, start: 0, end: 10}]}
  - name: top
    blend: override
    channels: [jaw, neck_pan]
    clips:
      - {clip: wave, start: 2, fade_in: 0.5, fade_out: 0.5}
      - {clip: wave, start: 4.5, speed: 1.5, offset: 1, reverse: true, fade_in: 0.5}
)";

TEST(ShowClips, LoadsClipsLayersAndPlacementsResolvingDefaultEnds) {
  const playback::Show show = load_show_file(avar::testing::write_temp_file("show.yaml", kClipsShow));
  EXPECT_TRUE(show.tracks.empty());
  ASSERT_EQ(show.clips.size(), 2u);
  EXPECT_EQ(show.clips[0].mode, playback::ClipMode::loop);
  EXPECT_EQ(show.clips[1].mode, playback::ClipMode::hold);
  EXPECT_EQ(show.clips[1].where.line, 4);
  ASSERT_EQ(show.layers.size(), 2u);
  EXPECT_EQ(show.layers[0].blend, playback::Blend::override);
  EXPECT_TRUE(show.layers[0].mask.empty());
  ASSERT_EQ(show.layers[1].mask.size(), 2u);
  EXPECT_EQ(show.layers[1].mask[1].channel, "neck_pan");
  EXPECT_EQ(show.layers[1].mask[1].where.line, 13);
  const playback::Placement& wave = show.layers[1].placements[0];
  EXPECT_EQ(wave.clip, 1u);
  EXPECT_DOUBLE_EQ(wave.end, 5);  // start + duration / speed
  const playback::Placement& back = show.layers[1].placements[1];
  EXPECT_DOUBLE_EQ(back.end, 4.5 + (3 - 1) / 1.5);
  EXPECT_TRUE(back.reverse);
  EXPECT_EQ(back.where.line, 16);
}

TEST(ShowClips, RejectsBadClipsAndLayersWithFileLineAndWhatWasExpected) {
  const std::pair<std::string, std::string> cases[] = {
      {replace(kClipsShow, "clip: wave, start: 2", "clip: wav, start: 2"), ":15:16: unknown clip 'wav'; expected one of the show's clips: idle, wave"},
      {replace(kClipsShow, "mode: hold", "mode: bounce"), ":6:11: unknown clip mode 'bounce'; expected one of: hold, loop, ping_pong"},
      {replace(kClipsShow, "blend: override", "blend: multiply"), ":12:12: unknown blend 'multiply'; expected one of: override, additive"},
      {replace(kClipsShow, "duration: 3", "duration: -3"),
       ":5:15: expected the duration of clip 'wave' to be more than 0 seconds, found '-3'"},
      {replace(kClipsShow, "speed: 1.5", "speed: 0"),
       ":16:41: expected the speed of clip 'wave' to be more than 0 clip seconds per show second (reverse: true plays it backwards), found 0"},
      {replace(kClipsShow, "speed: 1.5", "speed: .nan"), ":16:41: expected the speed (clip seconds per show second) to be a finite number, found '.nan'"},
      {replace(kClipsShow, "fade_in: 0.5, fade_out: 0.5", "fade_in: 2, fade_out: 1.5"),
       ":15:54: the fades of clip 'wave' (in 2 s + out 1.5 s) are longer than its placement (3 s, 2 to 5 s); expected them to fit within it"},
      {replace(kClipsShow, "{time: 3, value: 20}", "{time: 3.5, value: 20}"),
       ":8:41: key time 3.5 s of track 'jaw' is outside clip 'wave', which runs from 0 to 3 s"},
      {replace(kClipsShow, "tracks:\n      jaw: [{time: 0, value: 0}, {time: 3, value: 20}]", "tracks: {}"),
       ":7:13: clip 'wave' has no tracks; expected at least one channel with keys"},
      {replace(kClipsShow, "channels: [jaw, neck_pan]", "channels: []"),
       ":13:15: the mask of layer 'top' lists no channels; expected at least one (leave channels out for every channel its clips drive)"},
      {replace(kClipsShow, "channels: [jaw, neck_pan]", "channels: [jaw, jaw]"),
       ":13:21: channel 'jaw' is listed twice in the mask of layer 'top'; expected each once"},
      {replace(kClipsShow, "start: 4.5, speed: 1.5", "start: 8, speed: 0.5"),
       ":16:9: clip 'wave' from 8 s at speed 0.5 ends at 12 s, after the show's end 10 s; expected it to end by then (give an end, or "
       "lengthen the show)"},
      {replace(kClipsShow, "start: 0, end: 10", "start: 0, end: 11"),
       ":10:54: expected the end of clip 'idle' after its start 0 s and by the show's end 10 s, found 11 s"},
      {replace(kClipsShow, "fade_in: 0.5}", "fade_in: 0.5, fade: 1}"),
       ":16:86: unknown field 'fade' in a placement in layer 'top'; expected one of: clip, start, end, speed, offset, reverse, fade_in, "
       "fade_out"},
      {replace(kClipsShow, "offset: 1", "offset: 3"), ":16:54: expected the offset into clip 'wave' to be at least 0 and below its duration 3 s, found 3 s"},
      {replace(kClipsShow, "blend: override", "blend: override\n    weight: 1.5"), ":13:13: expected the weight of layer 'top' within [0, 1], found '1.5'"},
      {replace(kClipsShow, "name: top", "name: base"), ":11:5: layer 'base' is named twice; expected unique layer names"},
      {kClipsShow.substr(0, kClipsShow.find("layers:")), ":3:3: the show has clips but no layers; expected layers: placing them on the timeline"},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(clips_error(text), expected) << text;
}

TEST(ShowClips, TheWriterRoundTripsClipsAndLayersExactly) {
  for (const std::string& path : {kExample, avar::testing::write_temp_file("show.yaml", kClipsShow)}) {
    SCOPED_TRACE(path);
    const playback::Show original = load_show_file(path);
    const std::string copy = avar::testing::temp_path("layered-copy.yaml");
    write_show_file(copy, original, "round trip");
    const playback::Show again = load_show_file(copy);
    ASSERT_EQ(again.clips.size(), original.clips.size());
    for (std::size_t c = 0; c < original.clips.size(); ++c) {
      const playback::Clip& a = original.clips[c];
      const playback::Clip& b = again.clips[c];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(b.duration, a.duration);
      EXPECT_EQ(b.mode, a.mode);
      ASSERT_EQ(b.tracks.size(), a.tracks.size());
      for (std::size_t t = 0; t < a.tracks.size(); ++t) {
        EXPECT_EQ(b.tracks[t].channel, a.tracks[t].channel);
        for (double s = -1; s <= a.duration + 1; s += 0.0137) ASSERT_EQ(b.tracks[t].curve.evaluate(s), a.tracks[t].curve.evaluate(s));
      }
    }
    ASSERT_EQ(again.layers.size(), original.layers.size());
    for (std::size_t l = 0; l < original.layers.size(); ++l) {
      const playback::Layer& a = original.layers[l];
      const playback::Layer& b = again.layers[l];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(b.blend, a.blend);
      EXPECT_EQ(b.weight, a.weight);
      ASSERT_EQ(b.mask.size(), a.mask.size());
      for (std::size_t m = 0; m < a.mask.size(); ++m) EXPECT_EQ(b.mask[m].channel, a.mask[m].channel);
      ASSERT_EQ(b.placements.size(), a.placements.size());
      for (std::size_t p = 0; p < a.placements.size(); ++p) {
        const playback::Placement& x = a.placements[p];
        const playback::Placement& y = b.placements[p];
        EXPECT_EQ(y.clip, x.clip);
        EXPECT_EQ(y.start, x.start);
        EXPECT_EQ(y.end, x.end);
        EXPECT_EQ(y.speed, x.speed);
        EXPECT_EQ(y.offset, x.offset);
        EXPECT_EQ(y.reverse, x.reverse);
        EXPECT_EQ(y.fade_in, x.fade_in);
        EXPECT_EQ(y.fade_out, x.fade_out);
      }
    }
    EXPECT_EQ(again.tracks.size(), original.tracks.size());
  }
}

TEST(ShowClips, TheCheckRejectsUnknownChannelsInClipsAndMasksNamingTheRigsChannels) {
  const rig::Rig rig = load_rig_file(kClipsRig);
  const std::string path =
      avar::testing::write_temp_file("show.yaml", replace(replace(kClipsShow, "channels: [jaw, neck_pan]", "channels: [jaw, neck_yaw]"),
                                                          "      jaw: [", "      chin: ["));
  const ShowCheck check = check_show_against_rig(load_show_file(path), rig);
  ASSERT_EQ(check.errors.size(), 2u);
  EXPECT_EQ(check.errors[0].to_string(), path + ":8:7: unknown channel 'chin' in clip 'wave'; expected one of the rig 'hello-head' channels: " +
                                             rig.channel_names());
  EXPECT_EQ(check.errors[1].to_string(), path + ":13:21: unknown channel 'neck_yaw' in the mask of layer 'top'; expected one of the rig "
                                                "'hello-head' channels: " + rig.channel_names());
  const ShowCheck good = check_show_against_rig(load_show_file(kExample), rig);
  EXPECT_TRUE(good.ok());
  // Channels moved only by layers count as driven: only the two the example leaves alone warn.
  EXPECT_EQ(good.warnings.size(), 2u);
}

TEST(ShowClips, FeasibilityJudgesTheComposedMotionAndRetimeRefusesLayeredShows) {
  const rig::Rig rig = load_rig_file(kClipsRig);
  const playback::Show example = load_show_file(kExample);
  EXPECT_TRUE(check_feasibility(example, rig).empty());
  // The idle sway (10 deg in 2 s) played 40 times faster asks neck_pan for 200 deg/s, more than
  // its 180; and a cut with no fade jumps.
  const std::string fast = avar::testing::write_temp_file(
      "show.yaml", replace(replace(kClipsShow, "{clip: idle, start: 0, end: 10}", "{clip: idle, start: 0, end: 10, speed: 40}"),
                           "{clip: wave, start: 2, fade_in: 0.5, fade_out: 0.5}", "{clip: wave, start: 2, fade_out: 0.5, offset: 1.5}"));
  const std::vector<Infeasible> found = check_feasibility(load_show_file(fast), rig);
  bool speed = false, jump = false;
  for (const Infeasible& f : found) {
    if (f.kind == Infeasible::Kind::speed && f.channel == "neck_pan") {
      speed = true;
      EXPECT_EQ(f.where.line, 10) << f.to_string();  // the idle placement
      EXPECT_GT(f.required, f.allowed);
    }
    if (f.kind == Infeasible::Kind::jump && f.channel == "jaw") {
      jump = true;
      EXPECT_EQ(f.t0, 2);
      EXPECT_NEAR(f.required, 10, 1e-3);  // the wave starts 1.5 s in: 10 deg over the rest 0
      EXPECT_EQ(f.where.line, 15) << f.to_string();
    }
  }
  EXPECT_TRUE(speed);
  EXPECT_TRUE(jump);
  try {
    retime(example, rig);
    FAIL() << "a layered show was retimed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has layers of clips, which retiming cannot stretch honestly"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::config
