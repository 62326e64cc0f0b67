// The idle: section of a rig file: read against the rig's channels, clipped to their ranges,
// and every mistake named at its file:line:col by load_rig_file (the whole file is checked).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../support/input_errors.hpp"
#include "avar/config/idle_section.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

std::string idle_example_rig() {
  std::ifstream in(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string idle_rig_error(const std::string& text) { return testing::load_error(load_rig_file, text, "idle_rig.yaml"); }

TEST(IdleSection, TheExampleRigReadsWithEveryBehaviour) {
  const std::string path = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml";
  const rig::Rig rig = load_rig_file(path);
  const std::optional<playback::IdleSpec> spec = load_idle_section(rig, path);
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->limits.size(), rig.channels.size());
  ASSERT_EQ(spec->noise.size(), 1u);
  EXPECT_EQ(spec->noise[0].channel, *rig.find_channel("neck_roll"));
  ASSERT_TRUE(spec->blinks);
  EXPECT_EQ(spec->blinks->lids.size(), 2u);
  EXPECT_DOUBLE_EQ(spec->blinks->lids[0].closed, 0);
  ASSERT_TRUE(spec->gaze);
  EXPECT_EQ(spec->gaze->eyes_pan, rig.find_channel("eyes_pan"));
  EXPECT_EQ(spec->gaze->head_pan, rig.find_channel("neck_pan"));
  ASSERT_TRUE(spec->breathing);
  EXPECT_DOUBLE_EQ(spec->breathing->period_s, 4.5);
}

TEST(IdleSection, ARigWithoutOneHasNone) {
  const std::string path = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-head.yaml";
  EXPECT_FALSE(load_idle_section(load_rig_file(path), path));
}

TEST(IdleSection, TheGazeFieldIsClippedToTheEyesRoom) {
  const std::string text = testing::replace(idle_example_rig(), "field: {pan: [-25, 25]", "field: {pan: [-90, 25]");
  const std::string path = testing::write_temp_file("idle_clip.yaml", text);
  const rig::Rig rig = load_rig_file(path);
  const auto spec = load_idle_section(rig, path);
  ASSERT_TRUE(spec && spec->gaze);
  EXPECT_DOUBLE_EQ(spec->gaze->pan_min, -35);  // eyes_pan: -35..35 about rest 0
  EXPECT_DOUBLE_EQ(spec->gaze->pan_max, 25);
}

TEST(IdleSection, MistakesAreNamedWhereTheyStand) {
  const std::string rig = idle_example_rig();
  EXPECT_NE(idle_rig_error(testing::replace(rig, "neck_roll: {amplitude: 2", "neck_rol: {amplitude: 2"))
                .find("expected a noise channel to be a channel of the rig, found 'neck_rol'"),
            std::string::npos);
  const std::string interval = idle_rig_error(testing::replace(rig, "interval_s: [2, 6]", "interval_s: [0.2, 6]"));
  EXPECT_NE(interval.find("shortest blink interval"), std::string::npos) << interval;
  EXPECT_EQ(interval.rfind(":", 0), 0u);  // file:line:col first
  EXPECT_NE(idle_rig_error(testing::replace(rig, "interval_s: [2, 6]", "interval_s: [6, 2]")).find("at most its high end"),
            std::string::npos);
  EXPECT_NE(idle_rig_error(testing::replace(rig, "{open: 80, closed: 0}, lid_right", "{open: 80, closed: 120}, lid_right"))
                .find("closed value of lid 'lid_left'"),
            std::string::npos);
  EXPECT_NE(
      idle_rig_error(testing::replace(rig, "eyes: {pan: eyes_pan, tilt: eyes_tilt}", "eyes: {pan: eyes_pan, tilt: lid_left}"))
          .find("already driven by idle blinks"),
      std::string::npos);
  EXPECT_NE(idle_rig_error(testing::replace(rig, "fixation_s: [0.4, 2.5]",
                                            "fixation_s: [0.4, 2.5]\n    near: {probability: 0.5, distance_m: 0.3}"))
                .find("needs per-eye pan channels"),
            std::string::npos);
  EXPECT_NE(idle_rig_error(testing::replace(rig, "breathing: {period_s: 4.5", "breathing: {period: 4.5")).find("period"),
            std::string::npos);
  EXPECT_NE(
      idle_rig_error(testing::replace(rig, "double_probability: 0.15", "double_probability: 1.5")).find("double_probability"),
      std::string::npos);
  const std::string where = idle_rig_error(testing::replace(rig, "octaves: 2}", "octaves: 9}"));
  EXPECT_NE(where.find("octaves"), std::string::npos) << where;
}

TEST(IdleSection, VergenceTurnsEachEyeByHalfTheInterOcularAngle) {
  std::string text = testing::replace(idle_example_rig(), "eyes: {pan: eyes_pan, tilt: eyes_tilt}",
                                      "eyes: {left_pan: eyes_pan, right_pan: jaw, tilt: eyes_tilt}");
  text = testing::replace(text, "fixation_s: [0.4, 2.5]",
                          "fixation_s: [0.4, 2.5]\n    near: {probability: 0.3, distance_m: 0.5, interocular_m: 0.06}");
  const std::string path = testing::write_temp_file("idle_vergence.yaml", text);
  const rig::Rig rig = load_rig_file(path);
  const auto spec = load_idle_section(rig, path);
  ASSERT_TRUE(spec && spec->gaze);
  EXPECT_NEAR(spec->gaze->vergence, std::atan2(0.03, 0.5) * 180 / M_PI, 1e-12);
  EXPECT_DOUBLE_EQ(spec->gaze->near_probability, 0.3);
}

}  // namespace
}  // namespace avar::config
