// Hobby servos on a PCA9685 board, end to end: hello-head plays on the example rig's simulated
// board (the driver's writes applied as the chip applies them, each servo where its pulse says,
// within a count of the board's 4.88 µs), and the rig's pca9685 settings are checked whole.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/play_summary.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kPcaRig = AVAR_SOURCE_DIR "/examples/rigs/pca9685-head.yaml";

TEST(Pca9685Play, HelloHeadPlaysOnASimulatedBoardWithinACountOfEachPulse) {
  const testing::CliResult r =
      testing::run_avar({"play", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rig", kPcaRig, "--sim", "--fast"});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("PCA9685 link 'head' at 0x40 on simulated I2C bus"), std::string::npos) << r.out;
  // The summary's max err per channel: the commanded pulse rounded to the board's 4.88 us counts
  // (neck_pan: 0.12 deg per us, so at most 0.3 deg).
  const auto errors = testing::max_errors(r.out);
  EXPECT_EQ(errors.size(), 8u) << r.out;
  for (const auto& [channel, error] : errors) EXPECT_LE(error, 0.5) << channel << "\n" << r.out;
  EXPECT_EQ(r.out.find("bytes sent 0"), std::string::npos) << r.out;
}

TEST(Pca9685Play, TheRigsSettingsAreCheckedWhole) {
  const std::string head = "name: bad\nlinks:\n  head:\n    port: sim\n";
  const std::string rest =
      "channels:\n  jaw: {unit: deg, min: 0, max: 30, rest: 0}\n"
      "actuators:\n  - {channel: jaw, protocol: pca9685, link: head, output: OUTPUT, calibration: {min_us: 1200, max_us: "
      "1650}}\n";
  const auto check = [&](const std::string& settings, const std::string& output) {
    std::string body = rest;
    body.replace(body.find("OUTPUT"), 6, output);
    const std::string rig = testing::write_temp_file("pca.yaml", head + "    pca9685: " + settings + "\n" + body);
    return testing::run_avar({"check", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rig", rig});
  };
  const testing::CliResult address = check("{address: 0x80}", "0");
  EXPECT_EQ(address.code, kExitBadInput);
  EXPECT_NE(address.err.find("expected address from 3 to 119"), std::string::npos) << address.err;
  const testing::CliResult rate = check("{frequency: 2000}", "0");
  EXPECT_NE(rate.err.find("expected frequency from 24 to 1525 Hz"), std::string::npos) << rate.err;
  const testing::CliResult outputs = check("{outputs: push_pull}", "0");
  EXPECT_NE(outputs.err.find("expected outputs: totem_pole"), std::string::npos) << outputs.err;
  const testing::CliResult output = check("{}", "16");
  EXPECT_EQ(output.code, kExitBadInput);
  EXPECT_NE(output.err.find("output"), std::string::npos) << output.err;
}

}  // namespace
}  // namespace avar::app
