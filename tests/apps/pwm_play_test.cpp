// Hobby servos on a PWM chip's own outputs, end to end: hello-head plays on the example rig's
// simulated chip (each servo where its pulse says, to the nanosecond), and the rig's pwm settings
// are checked whole.
#include <gtest/gtest.h>

#include <string>

#include "../support/cli_run.hpp"
#include "../support/play_summary.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace pwm_play_test {

const std::string kPinRig = AVAR_SOURCE_DIR "/examples/rigs/pin-servo-head.yaml";

TEST(PwmPlay, HelloHeadPlaysOnASimulatedChipWhereEachPulseSays) {
  const testing::CliResult r =
      testing::run_avar({"play", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rig", kPinRig, "--sim", "--fast"});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("PWM link 'pins' on simulated PWM chip"), std::string::npos) << r.out;
  const auto errors = testing::max_errors(r.out);
  EXPECT_EQ(errors.size(), 8u) << r.out;
  for (const auto& [channel, error] : errors) EXPECT_LE(error, 0.001) << channel << "\n" << r.out;
}

TEST(PwmPlay, TheRigsSettingsAreCheckedWhole) {
  const auto check = [&](const std::string& settings, const std::string& actuator) {
    const std::string rig = testing::write_temp_file(
        "pwm.yaml", "name: bad\nlinks:\n  pins:\n    port: sim\n    pwm: " + settings +
                        "\nchannels:\n  jaw: {unit: deg, min: 0, max: 30, rest: 0}\nactuators:\n  - {channel: jaw, link: pins, " +
                        actuator + "}\n");
    return testing::run_avar({"check", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rig", rig});
  };
  const std::string good = "pin: 9, calibration: {min_us: 1200, max_us: 1650}";
  const testing::CliResult rate = check("{frequency: 20}", good);
  EXPECT_EQ(rate.code, kExitBadInput);
  EXPECT_NE(rate.err.find("expected frequency from 40 to 400 Hz"), std::string::npos) << rate.err;
  const testing::CliResult key = check("{period: 20}", good);
  EXPECT_NE(key.err.find("period"), std::string::npos) << key.err;
  const testing::CliResult pin = check("{}", "pin: 256, calibration: {min_us: 1200, max_us: 1650}");
  EXPECT_NE(pin.err.find("expected pin from 0 to 255"), std::string::npos) << pin.err;
  const testing::CliResult uncalibrated = check("{}", "pin: 9");
  EXPECT_NE(uncalibrated.err.find("calibration"), std::string::npos) << uncalibrated.err;
  const testing::CliResult period = check("{frequency: 400}", "pin: 9, calibration: {min_us: 1000, max_us: 2600}");
  EXPECT_EQ(period.code, kExitBadInput);
  EXPECT_NE(period.err.find("sends one pulse every 2500"), std::string::npos) << period.err;
}

}  // namespace pwm_play_test
}  // namespace avar::app
