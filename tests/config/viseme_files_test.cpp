// Mouth cues from Rhubarb (TSV, JSON) and Papagayo/Moho switch files; the visemes table in a rig
// (validated against its channels and limits) and the show's visemes: source, with golden poses.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/viseme_cues.hpp"
#include "avar/config/viseme_tracks.hpp"

namespace avar::config {
namespace {

constexpr const char* kVisemeTsv = "0.00\tX\n0.20\tD\n0.40\tA\n0.50\tX\n1.00\tX\n";

TEST(VisemeCues, RhubarbTsvHoldsEachShapeUntilTheNext) {
  const auto cues = read_viseme_cues(testing::write_temp_file("cues.tsv", kVisemeTsv), 24, {});
  ASSERT_EQ(cues.size(), 5u);
  EXPECT_EQ(cues[1].shape, "D");
  EXPECT_EQ(cues[1].start, 0.2);
  EXPECT_EQ(cues[1].end, 0.4);
  EXPECT_EQ(cues[1].where.line, 2);
  EXPECT_EQ(cues[4].start, cues[4].end);
}

TEST(VisemeCues, RhubarbJsonReadsStartEndValue) {
  const auto cues =
      read_viseme_cues(testing::write_temp_file("cues.json", R"({"metadata": {"soundFile": "a.wav", "duration": 0.5},
        "mouthCues": [{"start": 0.00, "end": 0.20, "value": "X"}, {"start": 0.20, "end": 0.35, "value": "B"}]})"),
                       24, {});
  ASSERT_EQ(cues.size(), 2u);
  EXPECT_EQ(cues[1].shape, "B");
  EXPECT_EQ(cues[1].end, 0.35);
}

TEST(VisemeCues, MohoSwitchFileCountsFramesFromOne) {
  const auto cues =
      read_viseme_cues(testing::write_temp_file("cues.dat", "MohoSwitch1\n1 rest\n13 MBP\n16 AI\n25 rest\n"), 24, {});
  ASSERT_EQ(cues.size(), 4u);
  EXPECT_EQ(cues[0].shape, "rest");
  EXPECT_DOUBLE_EQ(cues[1].start, 0.5);
  EXPECT_DOUBLE_EQ(cues[2].start, 15.0 / 24);
  EXPECT_DOUBLE_EQ(cues[2].end, 1.0);
}

TEST(VisemeCues, BadLinesNameFileLineAndColumn) {
  const auto load = [](const std::string& p) { (void)read_viseme_cues(p, 24, {}); };
  EXPECT_EQ(testing::load_error(load, "0.00\tX\nsoon\tA\n"), ":2:1: found 'soon'; expected a time in seconds (0 or more)");
  EXPECT_EQ(testing::load_error(load, "0.50\tX\n0.20\tA\n"),
            ":2:1: cue at 0.2 s comes before the previous one at 0.5 s; expected times in order");
  EXPECT_EQ(testing::load_error(load, "0.00 X extra\n"),
            ":1:1: found 3 fields; expected 'seconds<TAB>shape' (a Rhubarb TSV line)");
  EXPECT_EQ(testing::load_error(load, "MohoSwitch1\n1.5 rest\n"),
            ":2:1: found frame '1.5'; expected a whole frame number of 1 or more");
  EXPECT_EQ(testing::load_error(load, R"({"mouthCues": [{"start": 0, "value": "X"}]})"),
            R"(: mouthCues[0] has no number 'end'; expected {"start": s, "end": s, "value": shape})");
  EXPECT_EQ(testing::load_error(load, R"({"cues": []})"),
            R"(:1:1: found no 'mouthCues' list; expected Rhubarb's JSON output {"mouthCues": [{"start", "end", "value"}]})");
  EXPECT_EQ(testing::load_error(load, "\n\n"), ":1:1: found no mouth cues; expected at least one");
  EXPECT_EQ(testing::load_error(load, "{\"mouthCues\": [\n  {\"start\": 0,, }]}"),
            ":2:15: not valid JSON; expected Rhubarb's JSON output");
  // A fuzzer's find: a number past a double's range once escaped as a foreign exception.
  EXPECT_EQ(testing::load_error(load, "{\"mouthCues\": [\n  {\"start\": 61e308, \"end\": 1, \"value\": \"A\"}]}"),
            ":2:13: number '61e308' out of range; expected a time in seconds");
}

constexpr const char* kVisemeRig = AVAR_SOURCE_DIR "/examples/rigs/talking-skull.yaml";

TEST(VisemeTables, RigTableIsReadAndCheckedAgainstTheRig) {
  const rig::Rig rig = load_rig_file(kVisemeRig);
  const auto table = load_rig_visemes(kVisemeRig, rig);
  ASSERT_TRUE(table);
  EXPECT_EQ(table->channels.front(), "jaw");
  EXPECT_NE(table->find("X"), table->shapes.size());
  std::string text;
  {
    std::ifstream file(kVisemeRig);
    text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  const auto load = [](const std::string& p) { (void)load_rig_file(p); };
  const std::string too_wide = testing::load_error(load, testing::replace(text, "D: {jaw: 20,", "D: {jaw: 40,"));
  EXPECT_NE(too_wide.find("mouth shape 'D' sets 'jaw' to 40 deg; expected within its limits [0, 25]"), std::string::npos)
      << too_wide;
  const std::string unknown = testing::load_error(load, testing::replace(text, "D: {jaw: 20,", "D: {nose: 2, jaw: 20,"));
  EXPECT_NE(unknown.find("poses channel 'nose', which the rig does not have"), std::string::npos) << unknown;
  const std::string missing = testing::load_error(load, testing::replace(text, "D: {jaw: 20, ", "D: {"));
  EXPECT_NE(missing.find("the pose of mouth shape 'D' has no value for channel 'jaw'"), std::string::npos) << missing;
}

TEST(VisemeTables, ShowSourceGivesGoldenPosesAndStaysWithinThem) {
  const std::string cues = testing::write_temp_file("cues.tsv", kVisemeTsv);
  const std::string show_path = testing::write_temp_file(
      "show.yaml",
      "duration: 1.2\nvisemes:\n  file: " + std::filesystem::path(cues).filename().string() +
          "\n  tolerance: 0.001\n  table:\n    X: {jaw: 0, lips: 0}\n    A: {jaw: 0, lips: 10}\n    D: {jaw: 20, lips: 0}\n");
  const playback::Show show = load_show_file(show_path);
  ASSERT_EQ(show.tracks.size(), 2u);
  EXPECT_EQ(show.tracks[0].channel, "jaw");
  EXPECT_EQ(show.tracks[1].channel, "lips");
  playback::CurveCursor jaw_cursor, lips_cursor;
  // Hand-computed at t = 0.3 s (inside D): X [0, 0.2] 0.1 s behind (e^-2), A [0.4, 0.5] 0.1 s
  // ahead (e^-2), X [0.5, 1] 0.2 s ahead (e^-4), the final X point and the rest after it 0.7 s
  // ahead (e^-14 each).
  const double w = 1 + 2 * std::exp(-2.0) + std::exp(-4.0) + 2 * std::exp(-14.0);
  EXPECT_NEAR(show.tracks[0].curve.evaluate(0.3, jaw_cursor), 20 / w, 0.001);
  EXPECT_NEAR(show.tracks[1].curve.evaluate(0.3, lips_cursor), 10 * std::exp(-2.0) / w, 0.001);
  for (double t = 0; t <= 1.2; t += 0.001) {
    const double jaw = show.tracks[0].curve.evaluate(t, jaw_cursor), lips = show.tracks[1].curve.evaluate(t, lips_cursor);
    ASSERT_GE(jaw, 0.0) << t;
    ASSERT_LE(jaw, 20.0) << t;
    ASSERT_GE(lips, 0.0) << t;
    ASSERT_LE(lips, 10.0) << t;
  }
}

TEST(VisemeTables, ShowSourceRefusesAShapeMissingFromTheTableAndDoubleTracks) {
  const std::string cues = std::filesystem::path(testing::write_temp_file("cues.tsv", kVisemeTsv)).filename().string();
  const auto load = [](const std::string& p) { (void)load_show_file(p); };
  // The cue is at fault: the error names the cue file's line.
  try {
    (void)load_show_file(testing::write_temp_file(
        "show.yaml", "duration: 2\nvisemes:\n  file: " + cues + "\n  table:\n    X: {jaw: 0}\n    A: {jaw: 1}\n"));
    ADD_FAILURE() << "a shape missing from the table loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cues.tsv:2:1: mouth shape 'D' is not in the visemes table; expected one of: X, A"),
              std::string::npos)
        << e.what();
  }
  const std::string twice = testing::load_error(
      load, "duration: 2\ntracks:\n  jaw: [{time: 0, value: 0}]\nvisemes:\n  file: " + cues + "\n  table:\n    X: {jaw: 0}\n",
      "show2.yaml");
  EXPECT_EQ(twice, ":7:5: channel 'jaw' has a track and is posed by the visemes table; expected one or the other");
}

}  // namespace
}  // namespace avar::config
