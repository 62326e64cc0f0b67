// The lively example end to end: a show with behaviour layers samples the same twice, plays on
// the simulated head frame for frame as `avar sample` composes it at the tick rate, passes
// `avar check`, and is refused by `avar sample` without the rig its generators need.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kLivelyShow = AVAR_SOURCE_DIR "/examples/shows/lively-head.yaml";
const std::string kLivelyRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

double lively_number(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

TEST(LivelyShow, SamplingTwiceGivesTheSameNumbersAndTheBehaviourMoves) {
  const testing::CliResult a = testing::run_avar({"sample", kLivelyShow, "--rig", kLivelyRig, "--rate", "100"});
  const testing::CliResult b = testing::run_avar({"sample", kLivelyShow, "--rig", kLivelyRig, "--rate", "100"});
  ASSERT_EQ(a.code, kExitOk) << a.err;
  EXPECT_EQ(a.out, b.out);
  const auto rows = testing::csv_rows(a.out);
  // The clips' channels, then the behaviour layers' (the rig's order), as the mask lets them.
  ASSERT_EQ(rows[0], (std::vector<std::string>{"seconds", "neck_pan", "neck_tilt", "jaw", "eyes_pan", "eyes_tilt", "lid_left",
                                               "lid_right"}));
  ASSERT_EQ(rows.size(), 1u + 12 * 100 + 1);
  double eyes_min = 0, eyes_max = 0, lid_min = 100;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    eyes_min = std::min(eyes_min, lively_number(rows[i][4]));
    eyes_max = std::max(eyes_max, lively_number(rows[i][4]));
    lid_min = std::min(lid_min, lively_number(rows[i][6]));
  }
  EXPECT_GT(eyes_max - eyes_min, 10);  // saccades
  EXPECT_LT(lid_min, 10);              // blinks
  // Without a rig the generators have no channels or limits to work with.
  const testing::CliResult bare = testing::run_avar({"sample", kLivelyShow});
  EXPECT_EQ(bare.code, kExitBadInput);
  EXPECT_NE(
      bare.err.find("lively-head.yaml:40:7: layer 'life' has behaviour, whose generators need the rig's channels and limits; "
                    "expected --rig RIG"),
      std::string::npos)
      << bare.err;
}

TEST(LivelyShow, PlayOnTheSimulatorComposesWhatSampleDoesAtTheTickRate) {
  const std::string trace = testing::temp_path("lively-trace.csv");
  const testing::CliResult played =
      testing::run_avar({"play", kLivelyShow, "--rig", kLivelyRig, "--fast", "--sim", "--no-progress", "--trace", trace});
  ASSERT_EQ(played.code, kExitOk) << played.err << played.out;
  const testing::CliResult sampled =
      testing::run_avar({"sample", kLivelyShow, "--rig", kLivelyRig, "--rate", "50"});  // the rig's rate
  ASSERT_EQ(sampled.code, kExitOk) << sampled.err;
  const auto expected = testing::csv_rows(sampled.out);
  std::ifstream csv(trace);
  const auto rows = testing::csv_rows(csv);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  std::size_t first = 0;
  while (first < rows.size() && (first == 0 || rows[first][1] != "running")) ++first;
  ASSERT_LT(first, rows.size());
  std::size_t compared = 0;
  // Row k of the show plays at show time k / 50 s; the trace keeps 9 significant digits.
  for (std::size_t k = 0; k + 1 < expected.size() && first + k < rows.size() && rows[first + k][1] == "running"; ++k) {
    for (std::size_t c = 1; c < expected[0].size(); ++c) {
      const double want = lively_number(expected[k + 1][c]);
      const double got = lively_number(rows[first + k][column(expected[0][c] + ".target")]);
      ASSERT_NEAR(got, want, 1e-7 * std::max(1.0, std::abs(want))) << expected[0][c] << " at " << expected[k + 1][0] << " s";
    }
    ++compared;
  }
  EXPECT_EQ(compared, 12u * 50);
}

TEST(LivelyShow, CheckFitsTheRigWithinItsLimits) {
  const testing::CliResult r = testing::run_avar({"check", kLivelyShow, "--rig", kLivelyRig});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("1 clips on 3 layers (2 of behaviour)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 segment(s) ask more"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace avar::app
