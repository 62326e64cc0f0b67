// Rig files with GPIO: digital channels, gpio links whose actuators are output lines, and
// digital inputs (e-stop, controls, start buttons), each bad entry named with file:line:col.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "avar/config/feasibility.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"

namespace avar::config {
namespace {

std::string digital_rig_error(const std::string& text) {
  return avar::testing::load_error(load_rig_file, text, "gpio_rig_under_test.yaml");
}

const char* kGpioRig = R"(name: prop
links:
  props: {port: sim, gpio: {}}
  head: {port: sim, maestro: {model: mini12}}
channels:
  relay: {kind: digital}
  lamp: {kind: digital, rest: 1, unit: on}
  jaw: {unit: deg, min: 0, max: 30, rest: 0}
actuators:
  - {channel: relay, link: props, line: 17}
  - {channel: lamp, link: props, line: 27, active_low: true, failsafe: hold}
  - {channel: jaw, link: head, device_channel: 0, calibration: {min_us: 1200, max_us: 1650}}
digital_inputs:
  estop: {chip: sim, line: 4, active_low: true, bias: pull_up, debounce_ms: 5, role: estop}
  door: {chip: gpiochip0, line: 5, role: control}
  go: {chip: sim, line: 6, role: start}
)";

TEST(DigitalRig, LoadsDigitalChannelsGpioOutputsAndInputs) {
  const rig::Rig rig = load_rig_file(testing::write_temp_file("gpio_rig.yaml", kGpioRig));
  const rig::ChannelSpec& relay = rig.channels[0];
  EXPECT_TRUE(relay.digital());
  EXPECT_EQ(relay.min, 0);
  EXPECT_EQ(relay.max, 1);
  EXPECT_EQ(relay.rest, 0);
  EXPECT_TRUE(std::isinf(relay.max_velocity));
  EXPECT_EQ(rig.channels[1].rest, 1);
  EXPECT_FALSE(rig.channels[2].digital());
  EXPECT_EQ(rig.links[0].protocol, "gpio");
  EXPECT_EQ(rig.actuators[0].device_channel, 17);
  EXPECT_EQ(rig.actuators[1].options_as<rig::GpioOutputOptions>().active_low, true);
  EXPECT_EQ(rig.actuators[1].failsafe, rig::Failsafe::hold);
  EXPECT_EQ(rig.actuators[0].calibration.to_device(1.0), 1.0);

  ASSERT_EQ(rig.digital_inputs.size(), 3u);
  const rig::DigitalInputSpec& estop = rig.digital_inputs[0];
  EXPECT_EQ(estop.name, "estop");
  EXPECT_TRUE(estop.simulated());
  EXPECT_EQ(estop.line, 4u);
  EXPECT_TRUE(estop.active_low);
  EXPECT_EQ(estop.bias, firmware_iface::GpioBias::pull_up);
  EXPECT_DOUBLE_EQ(estop.debounce_s, 0.005);
  EXPECT_EQ(estop.role, rig::InputRole::estop);
  EXPECT_EQ(rig.digital_inputs[1].role, rig::InputRole::control);
  EXPECT_DOUBLE_EQ(rig.digital_inputs[1].debounce_s, 0.01);  // the default
  EXPECT_EQ(rig.digital_inputs[2].role, rig::InputRole::start);
  EXPECT_EQ(estop.where.line, 14);
}

TEST(DigitalRig, RejectsEachBadEntryWithWhereAndWhat) {
  using avar::testing::replace;
  const std::string rig = kGpioRig;
  EXPECT_EQ(digital_rig_error(replace(rig, "relay: {kind: digital}", "relay: {kind: digitl}")),
            ":6:17: unknown channel kind 'digitl'; expected analog (moves within limits) or digital (0 off, 1 on)");
  EXPECT_EQ(digital_rig_error(replace(rig, "relay: {kind: digital}", "relay: {kind: digital, max_velocity: 3}")),
            ":6:40: a digital channel switches at once, so max_velocity does not apply to digital channel 'relay'; remove it "
            "(or make the channel analog)");
  EXPECT_EQ(digital_rig_error(replace(rig, "relay: {kind: digital}", "relay: {kind: digital, max: 5}")),
            ":6:31: expected max of digital channel 'relay' to be 1 (a digital channel is 0, off, or 1, on), found '5'");
  EXPECT_EQ(digital_rig_error(replace(rig, "rest: 1, unit: on", "rest: 0.5, unit: on")),
            ":7:31: expected rest of digital channel 'lamp' to be 0 (off) or 1 (on), found '0.5'");
  EXPECT_EQ(digital_rig_error(replace(rig, "{channel: relay, link: props, line: 17}", "{channel: jaw, link: props, line: 17}")),
            ":10:5: a gpio line switches a digital channel, but channel 'jaw' is analog; give it kind: digital (0 off, 1 on)");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 17}", "line: 17, calibration: {min_us: 1}}")),
            ":10:58: actuators on gpio link 'props' take no calibration block; their keys are: line, active_low");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 17}", "line: 1024}")),
            ":10:41: expected line from 0 to 1023 on gpio link 'props', found '1024'");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 27,", "line: 17,")),
            ":11:40: line 17 of gpio link 'props' is used by two actuators");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 17}", "line: 17, active_low: maybe}")),
            ":10:57: expected active_low to be true or false, found 'maybe'");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 17}", "device_channel: 17}")),
            ":10:51: device_channel does not address a gpio actuator; expected line");
  EXPECT_EQ(digital_rig_error(replace(rig, "line: 17}", "line: 17, speed: 3}")),
            ":10:5: a gpio line switches at once; speed and acceleration do not apply to actuators on link 'props'");
  EXPECT_EQ(digital_rig_error(replace(rig, "role: estop}", "role: panic}")),
            ":14:86: unknown role 'panic' of digital input 'estop'; expected one of: estop (stops the figure), control (a live "
            "input), start (a show start button)");
  EXPECT_EQ(digital_rig_error(replace(rig, "bias: pull_up", "bias: up")),
            ":14:55: unknown bias 'up' of digital input 'estop'; expected one of: as_is, disabled, pull_up, pull_down");
  EXPECT_EQ(digital_rig_error(replace(rig, "debounce_ms: 5", "debounce_ms: -1")),
            ":14:77: expected debounce_ms of digital input 'estop' from 0 to 1000 milliseconds, found '-1'");
  EXPECT_EQ(digital_rig_error(replace(rig, "{chip: sim, line: 6,", "{chip: sim, line: 4,")),
            ":16:25: line 4 of chip 'sim' is already digital input 'estop' (line 14)");
  EXPECT_EQ(digital_rig_error(replace(rig, "{chip: sim, line: 6,", "{chip: sim, line: 17,")),
            ":16:25: line 17 of chip 'sim' is already the output of channel 'relay' on link 'props' (line 10)");
  EXPECT_EQ(digital_rig_error(replace(rig, "{chip: sim, line: 6, role: start}", "{chip: sim, line: 6}")),
            ":16:7: missing field 'role' in digital input 'go'");
  EXPECT_EQ(
      digital_rig_error(replace(rig, "{chip: sim, line: 6,", "{chip: sim, pin: 6,")),
      ":16:19: unknown field 'pin' in digital input 'go'; expected one of: chip, line, active_low, bias, debounce_ms, role");
}

TEST(DigitalRig, FeasibilitySkipsDigitalChannels) {
  const rig::Rig rig = load_rig_file(testing::write_temp_file("gpio_rig.yaml", kGpioRig));
  const playback::Show show = load_show_file(testing::write_temp_file("relay_show.yaml", R"(name: blink
duration: 2
tracks:
  relay:
    - {time: 0, value: 0, interpolation: step}
    - {time: 0.5, value: 1, interpolation: step}
    - {time: 1, value: 0, interpolation: linear}
    - {time: 1.01, value: 1}
)"));
  EXPECT_TRUE(check_feasibility(show, rig).empty());
}

}  // namespace
}  // namespace avar::config
