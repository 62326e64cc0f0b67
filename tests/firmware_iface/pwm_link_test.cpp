// Hobby servos on a PWM chip's outputs, at the PWM seam: start claims each output with the
// period and sends nothing, sends write each channel's pulse to the nanosecond and only when it
// changed, a released channel goes limp, release() switches everything off, a chip that refuses
// is counted, bad configurations are refused. The sysfs chip is driven against a directory laid
// out as the kernel's PWM class is (the attribute files a real chip has), so its writes are
// read back; a real chip is opened where the machine has one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "../support/temp_file.hpp"
#include "avar/firmware_iface/pwm_link.hpp"
#include "avar/firmware_iface/sysfs_pwm_chip.hpp"
#include "avar/sim/sim_pwm_chip.hpp"

namespace avar::firmware_iface {
namespace pwm_link_test {

// Two servos: channel 0 (-90..90 deg -> 1000..2000 us) on output 3, channel 1 (0..100 % ->
// 500..2500 us) on output 1.
PwmLinkConfig two_servos() {
  PwmLinkConfig c;
  c.outputs = {{0, 3, LinearCalibration{-90, 90, 1000, 2000, false, 0}}, {1, 1, LinearCalibration{0, 100, 500, 2500, false, 0}}};
  c.description = "PWM link 'head'";
  return c;
}

TEST(PwmLink, StartClaimsEachOutputWithThePeriodAndSendsNothing) {
  auto chip = std::make_shared<sim::SimPwmChip>(4);
  PwmLink link(chip, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  EXPECT_EQ(link.period_ns(), 20000000u);
  EXPECT_EQ(chip->period_ns(3), 20000000u);
  EXPECT_EQ(chip->period_ns(1), 20000000u);
  EXPECT_EQ(chip->pulse_us(3), 0);
  EXPECT_EQ(chip->changes(3), 0u);
}

TEST(PwmLink, PutsEachPulseOnItsOutputToTheNanosecondAndWritesOnlyChanges) {
  auto chip = std::make_shared<sim::SimPwmChip>(4);
  PwmLink link(chip, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  std::vector<double> frame = {0, 25};
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_DOUBLE_EQ(chip->pulse_us(3), 1500);
  EXPECT_DOUBLE_EQ(chip->pulse_us(1), 1000);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(chip->changes(3), 1u) << "nothing changed, nothing written";
  frame[0] = 0.00005;  // 0.28 ns: rounds to the same nanosecond
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(chip->changes(3), 1u);
  frame[0] = 45.0001;  // 1750.00056 us
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_DOUBLE_EQ(chip->pulse_us(3), 1750.001);
  frame[0] = 500;  // beyond the channel: saturated to the calibration's end
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_DOUBLE_EQ(chip->pulse_us(3), 2000);
  EXPECT_EQ(link.saturated_pulses(), 1u);
}

TEST(PwmLink, AReleasedChannelGoesLimpAndReleaseSwitchesEverythingOff) {
  auto chip = std::make_shared<sim::SimPwmChip>(4);
  PwmLink link(chip, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  const std::vector<double> frame = {0, 25};
  ASSERT_EQ(link.send(frame), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(chip->pulse_us(1), 0);
  EXPECT_DOUBLE_EQ(chip->pulse_us(3), 1500);
  ASSERT_EQ(link.release(), Status::ok);
  EXPECT_EQ(chip->pulse_us(3), 0);
  const std::uint64_t changes = chip->changes(3);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(chip->pulse_us(3), 0) << "released stays released";
  EXPECT_EQ(chip->changes(3), changes);
}

TEST(PwmLink, AChipThatRefusesIsCountedAndTriedAgain) {
  auto chip = std::make_shared<sim::SimPwmChip>(4);
  PwmLink link(chip, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  chip->set_failing(true);
  const std::vector<double> frame = {0, 25};
  EXPECT_EQ(link.send(frame), Status::io_error);
  EXPECT_EQ(link.counters().device_errors, 2u);
  chip->set_failing(false);
  EXPECT_EQ(link.send(frame), Status::ok);
  EXPECT_DOUBLE_EQ(chip->pulse_us(3), 1500);
}

TEST(PwmLink, RefusesBadConfigurationsAndOutputsTheChipLacks) {
  auto chip = std::make_shared<sim::SimPwmChip>(2);
  PwmLinkConfig twice = two_servos();
  twice.outputs[1].pin = 3;
  EXPECT_THROW(PwmLink(chip, twice), std::invalid_argument);
  PwmLinkConfig fast = two_servos();
  fast.frequency_hz = 500;  // 2 ms period: 2500 us pulses do not fit
  EXPECT_THROW(PwmLink(chip, fast), std::invalid_argument);
  PwmLinkConfig none = two_servos();
  none.outputs.clear();
  EXPECT_THROW(PwmLink(chip, none), std::invalid_argument);
  PwmLink link(chip, two_servos());  // output 3 on a chip with outputs 0 and 1
  EXPECT_EQ(link.start(), Status::io_error);
  EXPECT_NE(link.start_problem().find("has outputs 0 to 1, not 3"), std::string::npos) << link.start_problem();
}

/// A chip's directory as the kernel lays it out, output 1 already exported.
std::string fake_sysfs_chip(const std::string& root) {
  namespace fs = std::filesystem;
  const fs::path chip = fs::path(root) / "pwmchip0";
  fs::create_directories(chip / "pwm1");
  std::ofstream(chip / "npwm") << "2\n";
  std::ofstream(chip / "export");
  for (const char* attribute : {"period", "duty_cycle", "enable", "polarity"}) std::ofstream(chip / "pwm1" / attribute) << "0\n";
  return chip.string();
}

std::string read_attribute(const std::string& chip, const std::string& attribute) {
  std::ifstream in(chip + "/pwm1/" + attribute);
  std::string value;
  in >> value;
  return value;
}

TEST(SysfsPwmChip, SetsThePeriodThenWritesEachPulseAndSwitchesTheOutput) {
  const std::string root = testing::temp_path("sysfs");
  const std::string chip_dir = fake_sysfs_chip(root);
  std::unique_ptr<PwmChip> chip = open_pwm_chip("0", root);
  EXPECT_EQ(chip->describe(), "PWM chip " + chip_dir);
  chip->open_output(1, 20000000);
  EXPECT_EQ(read_attribute(chip_dir, "period"), "20000000");
  EXPECT_EQ(read_attribute(chip_dir, "duty_cycle"), "0");
  EXPECT_EQ(read_attribute(chip_dir, "enable"), "0");
  EXPECT_EQ(read_attribute(chip_dir, "polarity"), "normal");
  ASSERT_EQ(chip->set_pulse(1, 1500123), Status::ok);
  EXPECT_EQ(read_attribute(chip_dir, "duty_cycle"), "1500123");
  EXPECT_EQ(read_attribute(chip_dir, "enable"), "1");
  EXPECT_EQ(chip->set_pulse(1, 20000001), Status::out_of_range) << "longer than the period";
  ASSERT_EQ(chip->switch_off(1), Status::ok);
  EXPECT_EQ(read_attribute(chip_dir, "enable"), "0");
  EXPECT_THROW(chip->open_output(1, 20000000), std::runtime_error) << "opened twice";
  EXPECT_THROW(chip->open_output(2, 20000000), std::runtime_error) << "the chip has outputs 0 and 1";
  EXPECT_THROW(open_pwm_chip("pwmchip7", root), std::runtime_error);
  EXPECT_NO_THROW(open_pwm_chip(chip_dir, "/nowhere"));
}

TEST(SysfsPwmChip, AnAbsentChipSaysWhatThisMachineHas) {
  try {
    open_pwm_chip("pwmchip0", "/nowhere/pwm");
    FAIL() << "opened a chip that is not there";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "no PWM chip 'pwmchip0' (/nowhere/pwm/pwmchip0/npwm cannot be read; this machine has none: /nowhere/pwm is "
              "absent)");
  }
}

TEST(SysfsPwmChip, ARealChipOpensWhereThereIsOne) {
  if (!std::filesystem::exists("/sys/class/pwm/pwmchip0/npwm"))
    GTEST_SKIP() << "no PWM chip on this machine (/sys/class/pwm/pwmchip0 absent)";
  EXPECT_NO_THROW(open_pwm_chip("pwmchip0"));
}

}  // namespace pwm_link_test
}  // namespace avar::firmware_iface
