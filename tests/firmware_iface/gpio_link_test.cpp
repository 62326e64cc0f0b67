// The GPIO link on a simulated chip: lines requested at their rest, on from the middle of the
// calibration up, active-low inverted, set only on change, released lines driven off. And the
// libgpiod chip: what it says on a machine without one, and a real chip where there is one.

#include "avar/firmware_iface/gpio_link.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "avar/firmware_iface/libgpiod_chip.hpp"
#include "avar/sim/sim_gpio_chip.hpp"

namespace avar::firmware_iface {
namespace {

GpioLinkConfig gpio_two_outputs() {
  GpioLinkConfig config;
  config.description = "GPIO link 'props'";
  GpioOutput relay;
  relay.channel = 0;
  relay.line = 17;
  GpioOutput lamp;
  lamp.channel = 2;
  lamp.line = 27;
  lamp.active_low = true;
  lamp.initial = true;
  config.outputs = {relay, lamp};
  return config;
}

TEST(GpioLink, RequestsLinesAtRestAndSwitchesFromTheMiddleUp) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioLink link(chip, gpio_two_outputs());
  EXPECT_TRUE(chip->is_output(17));
  EXPECT_FALSE(chip->level(17));  // off
  EXPECT_FALSE(chip->level(27));  // on, active-low: low
  ASSERT_EQ(link.start(), Status::ok);

  const std::vector<std::pair<double, bool>> cases{{0.0, false}, {0.49, false}, {0.5, true}, {1.0, true}, {0.2, false}};
  for (const auto& [value, on] : cases) {
    ASSERT_EQ(link.send(std::vector<double>{value, 123, 0.0}), Status::ok);
    EXPECT_EQ(chip->level(17), on) << value;
    EXPECT_TRUE(chip->level(27));  // lamp off: active-low high
  }
  EXPECT_EQ(chip->output_changes(17), 2u);  // on once, off once
  EXPECT_EQ(link.line_sets(), 4u);          // the first send sets every line, then on and off
  EXPECT_EQ(link.counters().exchanges, cases.size());
}

TEST(GpioLink, ReleasedChannelsAndReleaseDriveTheirLinesOff) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioLink link(chip, gpio_two_outputs());
  ASSERT_EQ(link.send(std::vector<double>{1, 0, 1}), Status::ok);
  EXPECT_TRUE(chip->level(17));
  EXPECT_FALSE(chip->level(27));
  link.release_channel(0);
  ASSERT_EQ(link.send(std::vector<double>{1, 0, 1}), Status::ok);
  EXPECT_FALSE(chip->level(17));  // de-energised whatever the frame says
  EXPECT_FALSE(chip->level(27));  // still on
  ASSERT_EQ(link.release(), Status::ok);
  EXPECT_TRUE(chip->level(27));  // off: active-low high
  ASSERT_EQ(link.send(std::vector<double>{1, 0, 1}), Status::ok);
  EXPECT_TRUE(chip->level(27));
}

TEST(GpioLink, GivesItsLinesBackAndRejectsALineUsedTwice) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  { GpioLink link(chip, gpio_two_outputs()); }
  EXPECT_FALSE(chip->is_requested(17));
  GpioLinkConfig twice = gpio_two_outputs();
  twice.outputs[1].line = 17;
  EXPECT_THROW(GpioLink(chip, twice), std::invalid_argument);
  GpioLinkConfig beyond = gpio_two_outputs();
  beyond.outputs[1].line = 99;
  try {
    GpioLink link(chip, beyond);
    FAIL() << "line 99 does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "simulated GPIO chip 'sim' has 64 lines (0 to 63); line 99 does not exist");
  }
  EXPECT_FALSE(chip->is_requested(17));  // the failed link gave back what it had taken
}

bool gpio_machine_has_chips() { return !gpio_chip_names().empty(); }

TEST(LibgpiodChip, NamesTheMissingChipAndWhatTheMachineHas) {
  if (gpio_machine_has_chips()) GTEST_SKIP() << "this machine has GPIO chips; the message for none cannot be seen here";
  try {
    (void)open_gpio_chip("gpiochip0");
    FAIL() << "opened a chip on a machine without /dev/gpiochip*";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "no GPIO chip 'gpiochip0' (this machine has none: /dev/gpiochip* absent)");
  }
}

TEST(LibgpiodChip, OpensARealChipAndReadsALine) {
  if (!gpio_machine_has_chips()) GTEST_SKIP() << "no GPIO chip on this machine: /dev/gpiochip* absent";
  const std::string name = gpio_chip_names().front();
  std::unique_ptr<GpioChip> chip;
  try {
    chip = open_gpio_chip(name);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "cannot open /dev/" << name << ": " << e.what();
  }
  EXPECT_GT(chip->line_count(), 0u);
  EXPECT_NE(chip->describe().find(name), std::string::npos);
  // The last line as an input without events: a line other programs rarely hold.
  const unsigned line = chip->line_count() - 1;
  try {
    chip->request_input({line, false, GpioBias::as_is, false});
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "line " << line << " of " << name << " is not free: " << e.what();
  }
  bool value = false;
  EXPECT_EQ(chip->get(line, value), Status::ok);
  EXPECT_EQ(chip->set(line, true), Status::out_of_range);  // an input is not driven
  chip->release(line);
}

}  // namespace
}  // namespace avar::firmware_iface
