// Behaviour layers in show files: loading, the checks that need no rig (golden errors with
// file:line:column), the checks against a rig by the rig idle section's own reader (the same
// messages), binding, and the feasibility of the composed motion.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/feasibility.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/playback/runtime/sampler.hpp"

namespace avar::config {
namespace {

using avar::testing::replace;

const std::string kBehaviourRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

const std::string kBehaviourShow = R"(duration: 10
tracks:
  jaw: [{time: 0, value: 0}, {time: 10, value: 10}]
layers:
  - name: life
    blend: additive
    weight: 0.8
    channels: [eyes_pan, lid_left, neck_tilt]
    behaviour:
      seed: 7
      from: 2
      to: 8
      fade_in: 0.5
      fade_out: 0.5
      blinks: {lids: {lid_left: {open: 80, closed: 0}}, interval_s: [2, 6]}
      gaze: {eyes: {pan: eyes_pan}}
      breathing: {period_s: 4, channels: {neck_tilt: 1.5}}
)";

std::string behaviour_load_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }

/// The first error of checking `text` against hello-head ("" when it fits), after the file name.
std::string behaviour_rig_error(const std::string& text) {
  const std::string path = avar::testing::write_temp_file("show.yaml", text);
  const ShowCheck check = check_show_against_rig(load_show_file(path), load_rig_file(kBehaviourRig));
  if (check.ok()) return "";
  const std::string message = check.errors.front().to_string();
  return message.substr(message.rfind(path, 0) == 0 ? path.size() : 0);
}

TEST(ShowBehaviour, LoadsTheSpanFadesAndSeedUnboundUntilARigIsGiven) {
  playback::Show show = load_show_file(avar::testing::write_temp_file("show.yaml", kBehaviourShow));
  ASSERT_EQ(show.layers.size(), 1u);
  const playback::Layer& layer = show.layers[0];
  ASSERT_TRUE(layer.behaviour);
  EXPECT_TRUE(layer.placements.empty());
  EXPECT_EQ(layer.behaviour->seed, 7u);
  EXPECT_DOUBLE_EQ(layer.behaviour->from, 2);
  EXPECT_DOUBLE_EQ(layer.behaviour->to, 8);
  EXPECT_DOUBLE_EQ(layer.behaviour->fade_in, 0.5);
  EXPECT_EQ(layer.behaviour->where.line, 10);
  EXPECT_TRUE(has_unbound_behaviour(show));
  EXPECT_TRUE(playback::behaviour_channels(layer).empty());

  const rig::Rig rig = load_rig_file(kBehaviourRig);
  bind_show_behaviour(show, rig);
  EXPECT_FALSE(has_unbound_behaviour(show));
  const playback::LayerBehaviour& b = *show.layers[0].behaviour;
  ASSERT_EQ(b.channels.size(), rig.channels.size());
  ASSERT_TRUE(b.idle.blinks && b.idle.gaze && b.idle.breathing);
  EXPECT_EQ(b.idle.blinks->lids[0].channel, *rig.find_channel("lid_left"));
  EXPECT_EQ(b.idle.gaze->eyes_pan, rig.find_channel("eyes_pan"));
  EXPECT_DOUBLE_EQ(b.idle.breathing->period_s, 4);
  EXPECT_EQ(playback::behaviour_channels(show.layers[0]), (std::vector<std::string>{"neck_tilt", "eyes_pan", "lid_left"}));

  // Without a span the behaviour plays the whole show; without a seed, one from the layer's name.
  const playback::Show whole = load_show_file(avar::testing::write_temp_file(
      "show.yaml", replace(replace(replace(kBehaviourShow, "      seed: 7\n", ""), "      from: 2\n", ""), "      to: 8\n", "")));
  EXPECT_DOUBLE_EQ(whole.layers[0].behaviour->from, 0);
  EXPECT_DOUBLE_EQ(whole.layers[0].behaviour->to, 10);
  EXPECT_NE(whole.layers[0].behaviour->seed, 7u);
  const playback::Show again =
      load_show_file(avar::testing::write_temp_file("show.yaml", replace(kBehaviourShow, "      seed: 7\n", "")));
  EXPECT_EQ(again.layers[0].behaviour->seed, whole.layers[0].behaviour->seed);
}

TEST(ShowBehaviour, WithoutARigEverythingButTheChannelsIsCheckedWhereItStands) {
  const std::string generators =
      "      blinks: {lids: {lid_left: {open: 80, closed: 0}}, interval_s: [2, 6]}\n"
      "      gaze: {eyes: {pan: eyes_pan}}\n"
      "      breathing: {period_s: 4, channels: {neck_tilt: 1.5}}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {replace(kBehaviourShow, "seed: 7", "sed: 7"),
       ":10:7: unknown field 'sed' in the behaviour of layer 'life'; expected one of: seed, from, to, fade_in, fade_out, noise, "
       "blinks, gaze, breathing"},
      {replace(kBehaviourShow, "seed: 7", "seed: -1"),
       ":10:13: expected the seed of the behaviour of layer 'life' to be a whole number of at least 0, found '-1'"},
      {replace(kBehaviourShow, "from: 2", "from: 12"),
       ":11:13: expected the start of the behaviour of layer 'life' within the show, from 0 to before 10 s, found 12 s"},
      {replace(kBehaviourShow, "to: 8", "to: 1"),
       ":12:11: expected the end of the behaviour of layer 'life' after its start 2 s and by the show's end 10 s, found 1 s"},
      {replace(kBehaviourShow, "fade_out: 0.5", "fade_out: 6"),
       ":14:17: the fades of the behaviour of layer 'life' (in 0.5 s + out 6 s) are longer than its span (6 s, 2 to 8 s); "
       "expected them to fit within it"},
      {replace(kBehaviourShow, "fade_in: 0.5", "fade_in: -1"), ":13:16: expected fade_in to be at least 0 seconds, found -1 s"},
      {replace(kBehaviourShow, "    behaviour:", "    clips: [{clip: x}]\n    behaviour:"),
       ":11:7: layer 'life' has both clips and behaviour; expected one or the other (put the behaviour on a layer of its own)"},
      {replace(kBehaviourShow, "    behaviour:", "    behaviours:"),
       ":9:5: unknown field 'behaviours' in a layer; expected one of: name, blend, weight, channels, clips, behaviour"},
      {replace(kBehaviourShow, generators, ""),
       ":10:7: expected at least one of noise, blinks, gaze, breathing in the behaviour of layer 'life'"},
      // The idle section's own checks, with its own words.
      {replace(kBehaviourShow, "interval_s: [2, 6]", "interval_s: [6, 2]"),
       ":15:69: expected the low end of interval_s at most its high end"},
      {replace(kBehaviourShow, "interval_s: [2, 6]", "intervals: [2, 6]"),
       ":15:57: unknown field 'intervals' in the blinks; expected one of: lids, interval_s, double_probability, double_gap_s, "
       "close_s, "
       "hold_s, open_s"},
      {replace(kBehaviourShow, "period_s: 4", "period_s: 0.1"), ":17:29: expected period_s from 0.5 to 60, found '0.1'"},
      {replace(kBehaviourShow, "pan: eyes_pan}", "pan: lid_left}"),
       ":16:26: channel 'lid_left' is already driven by idle blinks; gaze needs a channel of its own"},
      {replace(kBehaviourShow, "gaze: {eyes: {pan: eyes_pan}}", "gaze: {look_at: {effectors: [eyes]}}"),
       ":16:23: look-at gaze runs from the rig's idle section, under the show; expected, in the behaviour of layer 'life', "
       "gaze with eye channels (eyes: {pan, tilt}), or a show target that aims the eyes (targets: {EFFECTOR: {aim: [x, y, z], "
       "...}})"},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(behaviour_load_error(text), expected) << text;
}

TEST(ShowBehaviour, TheRigChecksChannelsAndLimitsWithTheIdleSectionsWords) {
  EXPECT_EQ(behaviour_rig_error(kBehaviourShow), "");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {replace(kBehaviourShow, "pan: eyes_pan}", "pan: eye_pan}"),
       ":16:26: expected pan channel to be a channel of the rig, found 'eye_pan'"},
      {replace(kBehaviourShow, "closed: 0}", "closed: 120}"),
       ":15:52: expected the closed value of lid 'lid_left' (inside its soft margins) from 0 to 100, found '120'"},
      {replace(kBehaviourShow, "channels: [eyes_pan, lid_left, neck_tilt]", "channels: [eyes_pan, lid, neck_tilt]"),
       ":8:26: unknown channel 'lid' in the mask of layer 'life'; expected one of the rig 'hello-head' channels: jaw, neck_pan, "
       "neck_tilt, neck_roll, eyes_pan, eyes_tilt, lid_left, lid_right"},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(behaviour_rig_error(text), expected) << text;
  // Binding says the same, as an InputError.
  playback::Show show =
      load_show_file(avar::testing::write_temp_file("show.yaml", replace(kBehaviourShow, "pan: eyes_pan}", "pan: eye_pan}")));
  EXPECT_THROW(bind_show_behaviour(show, load_rig_file(kBehaviourRig)), InputError);
}

TEST(ShowBehaviour, TheWriterWritesBehaviourThatReadsBackToTheSameMotion) {
  const rig::Rig rig = load_rig_file(kBehaviourRig);
  playback::Show original = load_show_file(AVAR_SOURCE_DIR "/examples/shows/lively-head.yaml");
  const std::string path = avar::testing::temp_path("lively-written.yaml");
  write_show_file(path, original, "a test");
  playback::Show written = load_show_file(path);
  ASSERT_EQ(written.layers.size(), original.layers.size());
  bind_show_behaviour(original, rig);
  bind_show_behaviour(written, rig);
  std::vector<std::string> names;
  for (const rig::ChannelSpec& c : rig.channels) names.push_back(c.name);
  playback::Sampler a(original, names, rig.rest_frame()), b(written, names, rig.rest_frame());
  std::vector<double> fa(names.size()), fb(names.size());
  for (int k = 0; k <= 600; ++k) {
    a.sample(k * 0.02, fa);
    b.sample(k * 0.02, fb);
    ASSERT_EQ(fa, fb) << "t " << k * 0.02;
  }
}

TEST(ShowBehaviour, FeasibilityMeasuresTheGeneratedMotionAndListsACutWithoutAFadeAsAStep) {
  const rig::Rig rig = load_rig_file(kBehaviourRig);
  // The example's generators keep within the limits: nothing to report (unbound: the check binds).
  const playback::Show lively = load_show_file(AVAR_SOURCE_DIR "/examples/shows/lively-head.yaml");
  EXPECT_TRUE(check_feasibility(lively, rig).empty());
  // An override layer cut in without a fade: the lids jump from rest (20) to open (80) at 2 s.
  const std::string cut =
      replace(replace(replace(kBehaviourShow, "blend: additive", "blend: override"), "      fade_in: 0.5\n", ""),
              "interval_s: [2, 6]", "interval_s: [5, 6]");
  const playback::Show show = load_show_file(avar::testing::write_temp_file("show.yaml", cut));
  bool lid_step = false;
  for (const Infeasible& f : check_feasibility(show, rig)) {
    if (f.kind != Infeasible::Kind::jump || f.channel != "lid_left") continue;
    lid_step = true;
    EXPECT_DOUBLE_EQ(f.t0, 2);
    EXPECT_NEAR(f.required, 0.8 * 60, 1e-6);  // the layer's weight times the jump
    EXPECT_EQ(f.where.line, 10);              // the behaviour
  }
  EXPECT_TRUE(lid_step);
}

}  // namespace
}  // namespace avar::config
