// The layered example end to end: `avar sample` prints the composed channels the sampler plays,
// `avar play --fast` plays it on the simulated head, and `avar check` judges it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"
#include "avar/playback/runtime/sampler.hpp"

namespace avar::app {
namespace {

const std::string kLayeredShow = AVAR_SOURCE_DIR "/examples/shows/layered-head.yaml";
const std::string kLayeredRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

using Result = testing::CliResult;

TEST(LayeredShow, SampleWritesTheComposedChannelsOverTheRigsRestPose) {
  const Result r = testing::run_avar({"sample", kLayeredShow, "--rig", kLayeredRig, "--rate", "20"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::stringstream out(r.out);
  const auto rows = testing::csv_rows(out);
  // The show's tracks first, then the channels its layers touch, in file order.
  ASSERT_EQ(rows[0], (std::vector<std::string>{"seconds", "lid_left", "lid_right", "neck_pan", "neck_tilt", "eyes_pan", "jaw"}));
  ASSERT_EQ(rows.size(), 1u + 14 * 20 + 1);
  const rig::Rig rig = config::load_rig_file(kLayeredRig);
  const playback::Show show = config::load_show_file(kLayeredShow);
  std::vector<std::string> names;
  for (const auto& c : rig.channels) names.push_back(c.name);
  playback::Sampler sampler(show, names, rig.rest_frame());
  std::vector<double> frame(names.size());
  double jaw_max = 0, lid_min = 100;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double t = std::strtod(rows[i][0].c_str(), nullptr);
    sampler.sample(t, frame);
    for (std::size_t c = 1; c < rows[0].size(); ++c) {
      const auto at = static_cast<std::size_t>(std::find(names.begin(), names.end(), rows[0][c]) - names.begin());
      ASSERT_EQ(std::strtod(rows[i][c].c_str(), nullptr), frame[at]) << rows[0][c] << " at " << t;
    }
    jaw_max = std::max(jaw_max, frame[0]);
    if (t > 2 && t < 13) lid_min = std::min(lid_min, frame[6]);
  }
  EXPECT_GT(jaw_max, 10);  // the performance talks
  EXPECT_LT(lid_min, 30);  // the additive blinks close the lids from 90 %
  // Without a rig the composition is over 0 where the show has no track: the same here, whose
  // unlayered channels rest at 0 and whose lids have tracks.
  const Result bare = testing::run_avar({"sample", kLayeredShow, "--rate", "20"});
  EXPECT_EQ(bare.out, r.out);
}

TEST(LayeredShow, SampleRefusesARigWithoutTheShowsChannels) {
  const Result r = testing::run_avar({"sample", kLayeredShow, "--rig", AVAR_SOURCE_DIR "/examples/rigs/dynamixel-arm.yaml"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("layered-head.yaml:9:3: unknown channel 'lid_left'"), std::string::npos) << r.err;
}

TEST(LayeredShow, PlaysOnTheSimulatedHeadFollowingTheComposedTargets) {
  const std::string trace = testing::temp_path("layered-trace.csv");
  const Result r = testing::run_avar({"play", kLayeredShow, "--rig", kLayeredRig, "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("deadline misses 0"), std::string::npos) << r.out;
  std::ifstream csv(trace);
  const auto rows = testing::csv_rows(csv);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  double pan_max = 0, jaw_max = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    pan_max = std::max(pan_max, std::strtod(rows[i][column("neck_pan.measured")].c_str(), nullptr));
    jaw_max = std::max(jaw_max, std::strtod(rows[i][column("jaw.measured")].c_str(), nullptr));
  }
  EXPECT_GT(pan_max, 30);  // the look to the left, 35 deg
  EXPECT_GT(jaw_max, 10);  // the talk
}

TEST(LayeredShow, CheckFitsTheRigAndRetimeIsRefusedWithAReason) {
  const Result ok = testing::run_avar({"check", kLayeredShow, "--rig", kLayeredRig});
  ASSERT_EQ(ok.code, kExitOk) << ok.err << ok.out;
  EXPECT_NE(ok.out.find("4 clips on 3 layers"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("0 segment(s) ask more"), std::string::npos) << ok.out;
  const Result retime = testing::run_avar({"check", kLayeredShow, "--rig", kLayeredRig, "--retime", testing::temp_path("retimed.yaml")});
  EXPECT_EQ(retime.code, kExitBadInput);
  EXPECT_NE(retime.err.find("has layers of clips, which retiming cannot stretch honestly"), std::string::npos) << retime.err;
}

}  // namespace
}  // namespace avar::app
