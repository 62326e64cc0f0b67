#include "avar/config/rig_file.hpp"

#include "avar/rig/link_options.hpp"

#include <gtest/gtest.h>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include <string>

namespace avar::config {
namespace {

std::string rig_error(const std::string& text) { return avar::testing::load_error(load_rig_file, text, "rig_under_test.yaml"); }
using avar::testing::replace;

std::string write_temp(const std::string& name, const std::string& text) { return testing::write_temp_file(name, text); }

const char* kGoodRig = R"(name: two
links:
  head: {port: sim, baud: 115200, maestro: {model: mini12}}
channels:
  jaw: {unit: deg, min: 0, max: 30, rest: 0}
  pan: {unit: deg, min: -60, max: 60, rest: 0, max_velocity: 90, ramp_velocity: 30}
actuators:
  - {channel: jaw, protocol: maestro, link: head, device_channel: 0, calibration: {min_us: 1200, max_us: 1650}}
  - {channel: pan, protocol: maestro, link: head, device_channel: 3, calibration: {min_us: 1000, max_us: 2000, reverse: true, trim_us: 12}, speed: 120}
)";

TEST(RigFile, LoadsChannelsLinksAndActuatorsResolvedToIndices) {
  const rig::Rig rig = load_rig_file(write_temp("good_rig.yaml", kGoodRig));
  EXPECT_EQ(rig.name, "two");
  ASSERT_EQ(rig.channels.size(), 2u);
  EXPECT_EQ(rig.channels[1].name, "pan");
  EXPECT_DOUBLE_EQ(rig.channels[1].max_velocity, 90);
  EXPECT_DOUBLE_EQ(rig.channels[1].ramp_velocity, 30);
  EXPECT_DOUBLE_EQ(rig.channels[0].max_velocity, 120);  // default: 4 ranges per second
  EXPECT_DOUBLE_EQ(rig.channels[0].ramp_velocity, 15);  // default: half a range per second
  ASSERT_EQ(rig.links.size(), 1u);
  EXPECT_TRUE(rig.links[0].simulated());
  EXPECT_EQ(rig.links[0].options_as<rig::MaestroOptions>().channel_count, 12);
  ASSERT_EQ(rig.actuators.size(), 2u);
  EXPECT_EQ(rig.actuators[1].channel, rig::ChannelIndex{1});
  EXPECT_EQ(rig.actuators[1].device_channel, 3);
  EXPECT_TRUE(rig.actuators[1].calibration.reverse);
  EXPECT_DOUBLE_EQ(rig.actuators[1].calibration.trim, 12);
  EXPECT_DOUBLE_EQ(rig.actuators[1].calibration.channel_min, -60);
  EXPECT_DOUBLE_EQ(*rig.actuators[1].speed_limit, 120);
  EXPECT_EQ(rig.channels[1].where.line, 6);
}

TEST(RigFile, BundledExampleLoads) {
  const rig::Rig rig = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  EXPECT_EQ(rig.channels.size(), 8u);
  EXPECT_EQ(rig.actuators.size(), 8u);
}

TEST(RigFile, MissingFileIsNamed) {
  try {
    load_rig_file("/nonexistent/rig.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/rig.yaml: cannot read file: No such file or directory");
  }
}

TEST(RigFile, MalformedYamlGivesLineAndColumn) {
  EXPECT_EQ(rig_error("name: x\nchannels: {jaw: [1, 2}\n"), ":2:22: malformed YAML: illegal flow end");
}

TEST(RigFile, RejectsEachBadEntryWithWhereAndWhat) {
  EXPECT_EQ(rig_error(replace(kGoodRig, "name: two", "name: two\nspeed: 3")),
            ":2:1: unknown field 'speed' in the rig file; expected one of: name, rate_hz, links, channels, actuators, "
            "kinematics, digital_inputs, inputs, visemes, idle");
  EXPECT_EQ(rig_error(replace(kGoodRig, "{channel: jaw,", "{channel: chin,")),
            ":8:15: unknown channel 'chin'; expected one of the rig's channels: jaw, pan");
  EXPECT_EQ(rig_error(replace(kGoodRig, "{channel: jaw, protocol: maestro", "{channel: jaw, protocol: dynamixl")),
            ":8:30: unknown protocol 'dynamixl'; expected one of: maestro, dynamixel, feetech, ssc32, dmx, can, gpio, artnet, "
            "sacn, pca9685, avar-device, pwm");
  EXPECT_EQ(rig_error(replace(kGoodRig, "{channel: jaw, protocol: maestro", "{channel: jaw, protocol: dynamixel")),
            ":8:30: link 'head' speaks maestro, not dynamixel; expected protocol: maestro");
  EXPECT_EQ(rig_error(replace(kGoodRig, "device_channel: 3", "device_channel: 12")),
            ":9:67: expected device_channel from 0 to 11 on maestro link 'head', found '12'");
  EXPECT_EQ(rig_error(replace(kGoodRig, "device_channel: 3", "device_channel: 0")),
            ":9:67: device_channel 0 of maestro link 'head' is used by two actuators");
  EXPECT_EQ(rig_error(replace(kGoodRig, ", maestro: {model: mini12}", "")),
            ":3:9: expected link 'head' to name its protocol with a settings block, one of: maestro, dynamixel, feetech, "
            "ssc32, dmx, can, gpio, artnet, sacn, pca9685, avar-device, pwm (for example `dynamixel: {}`)");
  EXPECT_EQ(rig_error(replace(kGoodRig, "maestro: {model: mini12}", "maestro: {model: mini12}, dmx: {}")),
            ":3:66: link 'head' names two protocols; expected exactly one of: maestro, dynamixel, feetech, ssc32, dmx, can, "
            "gpio, artnet, sacn, pca9685, avar-device, pwm");
  EXPECT_EQ(rig_error(replace(kGoodRig, "max: 30, rest: 0", "max: -3, rest: 0")),
            ":5:33: expected max of channel 'jaw' to be greater than its min 0, found -3");
  EXPECT_EQ(rig_error(replace(kGoodRig, "max: 30, rest: 0", "max: 30, rest: 40")),
            ":5:43: expected rest of channel 'jaw' inside its limits [0, 30], found 40");
  EXPECT_EQ(rig_error(replace(kGoodRig, "baud: 115200", "baud: 12345")),
            ":3:27: expected a standard serial baud rate (9600, 19200, 38400, 57600, 115200, 230400, 1000000...), found '12345'");
  EXPECT_EQ(rig_error(replace(kGoodRig, "baud: 115200", "baud: 115200, watchdog_ms: 0")),
            ":3:48: expected watchdog_ms of link 'head' from 1 to 60000 milliseconds, found '0'");
  EXPECT_EQ(rig_error(replace(kGoodRig, "max: 30, rest: 0", "max: 30, rest: 0, soft_margin: 20")),
            ":5:59: expected soft_margin of channel 'jaw' from 0 to less than half the range (15), found '20'");
  EXPECT_EQ(rig_error(replace(kGoodRig, "device_channel: 3,", "device_channel: 3, failsafe: drop,")),
            ":9:80: unknown fail-safe action 'drop'; expected one of: hold, rest, release");
  EXPECT_EQ(rig_error(replace(kGoodRig, "model: mini12", "model: mega")),
            ":3:52: unknown Maestro model 'mega'; expected one of: micro6, mini12, mini18, mini24");
  EXPECT_EQ(rig_error(replace(kGoodRig, "max: 30, rest: 0", "max: thirty, rest: 0")),
            ":5:33: expected max of channel 'jaw' to be a finite number, found 'thirty'");
  EXPECT_EQ(rig_error(replace(kGoodRig, "min_us: 1200, max_us: 1650", "min_us: 1200")),
            ":8:83: missing field 'max_us' in the calibration of actuator 1");
  EXPECT_EQ(rig_error(replace(kGoodRig, "link: head, device_channel: 0", "link: body, device_channel: 0")),
            ":8:45: unknown link 'body'; expected one of the rig's links: head");
}

const char* kBusRig = R"(name: bus
links:
  arm: {port: sim, baud: 1000000, dynamixel: {readback: position, reply_timeout_ms: 5, retries: 2}}
  legs: {port: sim, feetech: {series: scs}}
  board: {port: sim, baud: 115200, ssc32: {}}
  lights: {port: sim, dmx: {}}
channels:
  shoulder: {unit: deg, min: -90, max: 90, rest: 0}
  knee: {unit: deg, min: 0, max: 120, rest: 10}
  tail: {unit: deg, min: -45, max: 45, rest: 0}
  glow: {unit: '%', min: 0, max: 100, rest: 0}
  spot: {unit: '%', min: 0, max: 100, rest: 0}
actuators:
  - {channel: shoulder, link: arm, id: 1, calibration: {min_position: 1024, max_position: 3072}, failsafe: release}
  - {channel: knee, link: legs, id: 7, calibration: {min_position: 200, max_position: 800, reverse: true}}
  - {channel: tail, link: board, device_channel: 31, calibration: {min_us: 900, max_us: 2100}}
  - {channel: glow, link: lights, address: 1}
  - {channel: spot, link: lights, address: 2, fine: true, calibration: {min_level: 0, max_level: 65535}}
)";

TEST(RigFile, EveryProtocolLoadsWithItsAddressingAndSettings) {
  const rig::Rig rig = load_rig_file(write_temp("bus.yaml", kBusRig));
  ASSERT_EQ(rig.links.size(), 4u);
  EXPECT_EQ(rig.links[0].protocol, "dynamixel");
  const rig::ServoBusOptions bus = rig.links[0].options_as<rig::DynamixelOptions>().bus;
  EXPECT_EQ(bus.readback, rig::Readback::position);
  EXPECT_EQ(bus.reply_timeout_ms, 5);
  EXPECT_EQ(bus.retries, 2);
  EXPECT_EQ(rig.links[1].protocol, "feetech");
  EXPECT_EQ(rig.links[1].options_as<rig::FeetechOptions>().series, rig::FeetechSeries::scs);
  EXPECT_EQ(rig.links[1].baud, 1000000);  // Feetech's factory rate
  EXPECT_EQ(rig.links[2].protocol, "ssc32");
  EXPECT_EQ(rig.links[3].protocol, "dmx");
  EXPECT_EQ(rig.actuators[0].device_channel, 1);
  EXPECT_DOUBLE_EQ(rig.actuators[0].calibration.device_at_max, 3072);
  EXPECT_EQ(rig.actuators[1].device_channel, 7);
  EXPECT_TRUE(rig.actuators[1].calibration.reverse);
  EXPECT_EQ(rig.actuators[2].device_channel, 31);
  // A dimmer without calibration spans the full 8-bit range.
  EXPECT_DOUBLE_EQ(rig.actuators[3].calibration.device_at_min, 0);
  EXPECT_DOUBLE_EQ(rig.actuators[3].calibration.device_at_max, 255);
  EXPECT_TRUE(rig.actuators[4].fine);
  EXPECT_DOUBLE_EQ(rig.actuators[4].calibration.device_at_max, 65535);
}

TEST(RigFile, RejectsBadBusEntriesWithWhereAndWhat) {
  EXPECT_EQ(rig_error(replace(kBusRig, "baud: 1000000, dynamixel", "baud: 500000, dynamixel")),
            ":3:26: a dynamixel device cannot run at '500000' baud; expected one of: 9600, 57600, 115200, 1000000, 2000000, "
            "3000000, 4000000");
  EXPECT_EQ(rig_error(replace(kBusRig, "baud: 115200, ssc32", "baud: 57600, ssc32")),
            ":5:28: a ssc32 device cannot run at '57600' baud; expected one of: 2400, 9600, 38400, 115200");
  EXPECT_EQ(rig_error(replace(kBusRig, "id: 7,", "id: 254,")),
            ":15:37: expected id from 0 to 253 on feetech link 'legs', found '254'");
  EXPECT_EQ(rig_error(replace(kBusRig, "link: arm, id: 1,", "link: arm, id: 253,")),
            ":14:40: expected id from 0 to 252 on dynamixel link 'arm', found '253'");
  EXPECT_EQ(rig_error(replace(kBusRig, "link: legs, id: 7,", "link: arm, id: 1,")),
            ":15:36: id 1 of dynamixel link 'arm' is used by two actuators");
  EXPECT_EQ(rig_error(replace(kBusRig, "address: 1}", "address: 3}")),
            ":18:44: address 3 of dmx link 'lights' is used by two actuators");
  EXPECT_EQ(rig_error(replace(kBusRig, "address: 2, fine", "address: 512, fine")),
            ":18:44: expected address from 1 to 511 on dmx link 'lights', found '512'");
  EXPECT_EQ(rig_error(replace(kBusRig, "link: arm, id: 1", "link: arm, device_channel: 1")),
            ":14:52: device_channel does not address a dynamixel actuator; expected id");
  EXPECT_EQ(rig_error(replace(kBusRig, "max_position: 800", "max_position: 1800")),
            ":15:87: expected max_position from 0 to 1023 position steps, found '1800'");
  EXPECT_EQ(rig_error(replace(kBusRig, "readback: position", "readback: everything")),
            ":3:57: unknown readback 'everything'; expected one of: none, position, full");
  EXPECT_EQ(rig_error(replace(kBusRig, "series: scs", "series: sms")),
            ":4:39: unknown Feetech series 'sms'; expected one of: sts, scs");
  EXPECT_EQ(rig_error(replace(kBusRig, "address: 1}", "address: 1, fine: true}")),
            ":18:44: address 2 of dmx link 'lights' is used by two actuators");
  EXPECT_EQ(rig_error(replace(kBusRig, "device_channel: 31,", "device_channel: 31, fine: true,")),
            ":16:60: fine (16-bit DMX) applies to dmx links only; link 'board' speaks ssc32");
}

}  // namespace
}  // namespace avar::config
