// The path-target example plays end to end: `avar check` accepts it on its rig and `avar play
// --fast` runs it on the simulated head, every inverse-kinematics solve converging.
#include <gtest/gtest.h>

#include <string>

#include "../support/cli_run.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kGazeRig = AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml";
const std::string kFigureEightShow = AVAR_SOURCE_DIR "/examples/shows/figure-eight.yaml";

TEST(PlayPathExample, ChecksAndPlaysTheFigureEightOnTheGazeHead) {
  const testing::CliResult check = testing::run_avar({"check", kFigureEightShow, "--rig", kGazeRig});
  ASSERT_EQ(check.code, kExitOk) << check.err << check.out;
  const testing::CliResult play = testing::run_avar({"play", kFigureEightShow, "--rig", kGazeRig, "--sim", "--fast", "--no-progress"});
  ASSERT_EQ(play.code, kExitOk) << play.err << play.out;
  EXPECT_NE(play.out.find("neck_pan"), std::string::npos) << play.out;
  EXPECT_NE(play.out.find(" 0 degraded (target out of reach: closest pose used), 0 failed"), std::string::npos) << play.out;
}

}  // namespace
}  // namespace avar::app
