// A figure on a board running avar's streaming player, end to end through `avar play`: hello-head
// plays on the example rig's simulated board (the player's own source) and tracks as well as the
// same figure on a Maestro fed a position every tick, the tracking check allowing for the lead
// the board plays behind, and the rig's avar-device settings are checked whole.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"
#include "../support/play_summary.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kHelloShow = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";
const std::string kStreamingRig = AVAR_SOURCE_DIR "/examples/rigs/streaming-head.yaml";

TEST(AvarDevicePlay, HelloHeadStreamsAsCloseAsAMaestroFedEveryTick) {
  const testing::CliResult streamed = testing::run_avar({"play", kHelloShow, "--rig", kStreamingRig, "--sim", "--fast"});
  ASSERT_EQ(streamed.code, kExitOk) << streamed.err << streamed.out;
  EXPECT_NE(streamed.out.find("simulated avar-device (115200 baud, device at 200 Hz)"), std::string::npos) << streamed.out;
  const testing::CliResult direct =
      testing::run_avar({"play", kHelloShow, "--rig", AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml", "--sim", "--fast"});
  ASSERT_EQ(direct.code, kExitOk) << direct.err;
  const auto s = testing::max_errors(streamed.out), d = testing::max_errors(direct.out);
  ASSERT_EQ(s.size(), 8u) << streamed.out;
  ASSERT_EQ(d.size(), 8u) << direct.out;
  // The same servo model behind both: the knots' cubic and the board's own ticks add nothing
  // worth a tenth of a unit, and the board's 150 ms lead is not counted as error.
  for (const auto& [channel, error] : s) EXPECT_LE(error, d.at(channel) + 0.1) << channel << "\n" << streamed.out;
}

TEST(AvarDevicePlay, ATrackingToleranceAllowsForTheLead) {
  // neck_pan lags its command by 150 ms on the board (16 degrees at its speed): within 5 degrees
  // of the command of 150 ms ago, the tolerance holds.
  std::ifstream file(kStreamingRig);
  std::stringstream text;
  text << file.rdbuf();
  std::string rig = text.str();
  const std::string pan = "neck_pan:  {unit: deg, min: -60, max: 60,  rest: 0, max_velocity: 180";
  ASSERT_NE(rig.find(pan), std::string::npos);
  rig.replace(rig.find(pan), pan.size(), pan + ", tracking_tolerance: 5");
  const std::string path = testing::write_temp_file("streaming-tolerance.yaml", rig);
  const testing::CliResult r = testing::run_avar({"play", kHelloShow, "--rig", path, "--sim", "--fast"});
  EXPECT_EQ(r.code, kExitOk) << r.err << r.out;
}

TEST(AvarDevicePlay, TheRigsSettingsAreCheckedWhole) {
  const auto play = [](const std::string& settings, const std::string& outputs) {
    const std::string rig = testing::write_temp_file(
        "avar-device.yaml", "name: bad\nrate_hz: 100\nlinks:\n  head: {port: sim, avar-device: " + settings +
                                "}\nchannels:\n  jaw: {unit: deg, min: 0, max: 30, rest: 0}\n"
                                "  pan: {unit: deg, min: -60, max: 60, rest: 0}\nactuators:\n" +
                                outputs);
    const std::string show = testing::write_temp_file(
        "two.yaml",
        "name: two\nduration: 1\ntracks:\n  jaw:\n    - {time: 0, value: 0}\n    - {time: 1, value: 20}\n"
        "  pan:\n    - {time: 0, value: 0}\n    - {time: 1, value: -30}\n");
    return testing::run_avar({"play", show, "--rig", rig, "--sim", "--fast"});
  };
  const std::string good =
      "  - {channel: jaw, link: head, output: 0, calibration: {min_us: 1200, max_us: 1650}}\n"
      "  - {channel: pan, link: head, output: 1, calibration: {min_us: 1000, max_us: 2000}}\n";
  const testing::CliResult lead = play("{knot_ms: 50, lead_ms: 100}", good);
  EXPECT_EQ(lead.code, kExitBadInput);
  EXPECT_NE(lead.err.find("expected lead_ms of at least 3 knots (150 ms with knot_ms 50), found '100'"), std::string::npos)
      << lead.err;
  const testing::CliResult knots = play("{lead_ms: 400, device_knots: 6}", good);
  EXPECT_EQ(knots.code, kExitBadInput);
  EXPECT_NE(knots.err.find("expected device_knots of at least 10"), std::string::npos) << knots.err;
  const testing::CliResult key = play("{knots_ms: 50}", good);
  EXPECT_EQ(key.code, kExitBadInput);
  EXPECT_NE(key.err.find("knots_ms"), std::string::npos) << key.err;
  const testing::CliResult gap = play("{}",
                                      "  - {channel: jaw, link: head, output: 0, calibration: {min_us: 1200, max_us: 1650}}\n"
                                      "  - {channel: pan, link: head, output: 2, calibration: {min_us: 1000, max_us: 2000}}\n");
  EXPECT_EQ(gap.code, kExitBadInput);
  EXPECT_NE(gap.err.find("output 2 of avar-device link 'head' is outside 0..1"), std::string::npos) << gap.err;
}

}  // namespace
}  // namespace avar::app
