// The talking-skull example end to end: its voice made with espeak-ng next to a copy of the show,
// checked against its rig and played on the simulator; the measured jaw opens while the voice
// speaks and rests in the silence before it. `avar visemes` on the example's Rhubarb TSV.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

namespace fs = std::filesystem;
constexpr const char* kSkullRig = AVAR_SOURCE_DIR "/examples/rigs/talking-skull.yaml";

TEST(TalkingSkull, ExamplePlaysWithTheJawFollowingTheVoice) {
  if (std::system("command -v espeak-ng > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "espeak-ng is not installed (Debian package espeak-ng)";
  const fs::path dir = testing::temp_path("skull");
  fs::create_directories(dir);
  for (const char* name : {"talking-skull.yaml", "talking-skull.tsv"})
    fs::copy_file(fs::path(AVAR_SOURCE_DIR "/examples/shows") / name, dir / name);
  // The same command as the Makefile's demo-talking target.
  const std::string speak =
      "espeak-ng -s 140 -w '" + (dir / "talking-skull.wav").string() + "' 'Good evening. Welcome to my haunted house.'";
  ASSERT_EQ(std::system(speak.c_str()), 0) << speak;
  const std::string show = (dir / "talking-skull.yaml").string();
  const auto check = testing::run_avar({"check", show, "--rig", kSkullRig});
  ASSERT_EQ(check.code, kExitOk) << check.err << check.out;
  EXPECT_EQ(check.err.find("warning"), std::string::npos) << "every channel driven, no overshoot: " << check.err;

  const std::string trace = testing::temp_path("trace.csv");
  const auto play = testing::run_avar({"play", show, "--rig", kSkullRig, "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(play.code, kExitOk) << play.err << play.out;
  std::ifstream csv(trace);
  const auto rows = testing::csv_rows(csv);
  ASSERT_GT(rows.size(), 100u);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const std::size_t time = 0, phase = 1, jaw = column("jaw.measured"), lips = column("lip_corners.measured");
  ASSERT_LT(jaw, rows[0].size());
  ASSERT_LT(lips, rows[0].size());
  // Show time: the trace's seconds count from the glide in; the show starts with `running`.
  std::size_t first = 1;
  while (first < rows.size() && rows[first][phase] != "running") ++first;
  ASSERT_LT(first, rows.size());
  const double show_start = std::strtod(rows[first][time].c_str(), nullptr);
  double jaw_before = 0, jaw_speaking = 0, lips_speaking = 0;
  for (std::size_t i = first; i < rows.size() && rows[i][phase] == "running"; ++i) {
    const double t = std::strtod(rows[i][time].c_str(), nullptr) - show_start;
    const double j = std::strtod(rows[i][jaw].c_str(), nullptr);
    if (t < 0.35) jaw_before = std::max(jaw_before, j);
    if (t > 0.5 && t < 3.6) {
      jaw_speaking = std::max(jaw_speaking, j);
      lips_speaking = std::max(lips_speaking, std::abs(std::strtod(rows[i][lips].c_str(), nullptr)));
    }
  }
  EXPECT_EQ(jaw_before, 0.0) << "the jaw rests before the voice";
  EXPECT_GT(jaw_speaking, 11.0) << "the jaw opens past half its travel while speaking";
  EXPECT_GT(lips_speaking, 3.0) << "the lip corners follow the mouth shapes";
}

TEST(TalkingSkull, VisemesCommandPosesTheRigFromTheExampleCues) {
  const std::string out = testing::temp_path("lips.yaml");
  const auto r =
      testing::run_avar({"visemes", AVAR_SOURCE_DIR "/examples/shows/talking-skull.tsv", "--rig", kSkullRig, "--out", out});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("30 mouth cues, 3.5 s; 9 shapes posing 4 channels"), std::string::npos) << r.out;
  const playback::Show show = config::load_show_file(out);
  EXPECT_EQ(show.duration, 4.0);
  ASSERT_EQ(show.tracks.size(), 4u);
  EXPECT_EQ(show.tracks[0].channel, "jaw");
  // The wide-open D at 1.88-2.10 s opens the jaw; rest (X) at the end closes it.
  playback::CurveCursor cursor;
  EXPECT_GT(show.tracks[0].curve.evaluate(2.0, cursor), 14.0);
  EXPECT_NEAR(show.tracks[0].curve.evaluate(3.45, cursor), 0.0, 0.3);

  const auto none = testing::run_avar({"visemes", AVAR_SOURCE_DIR "/examples/shows/talking-skull.tsv", "--rig",
                                       AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml", "--out", out});
  EXPECT_EQ(none.code, kExitBadInput);
  EXPECT_NE(none.err.find("has no visemes: table"), std::string::npos) << none.err;
  const auto missing = testing::run_avar({"visemes", testing::temp_path("none.tsv"), "--rig", kSkullRig, "--out", out});
  EXPECT_EQ(missing.code, kExitBadInput);
  EXPECT_NE(missing.err.find("cannot open mouth-cue file"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace avar::app
