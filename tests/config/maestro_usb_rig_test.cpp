// A Maestro on native USB in a rig file: `maestro: {model, usb: SERIAL}` needs no port; the
// serial-only settings, a port beside usb, and a malformed serial number are refused at their
// file:line:column.
#include <gtest/gtest.h>

#include "../support/input_errors.hpp"
#include "avar/rig/link_options.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

std::string usb_rig_error(const std::string& text) {
  return avar::testing::load_error(load_rig_file, text, "maestro_usb_rig.yaml");
}
using avar::testing::replace;

const char* kUsbRig = R"(name: head
links:
  head: {maestro: {model: micro6, usb: "00012345"}}
channels:
  jaw: {unit: deg, min: 0, max: 30, rest: 0}
actuators:
  - {channel: jaw, protocol: maestro, link: head, device_channel: 5, calibration: {min_us: 1200, max_us: 1650}}
)";

TEST(MaestroUsbRig, LoadsWithoutAPortAndWithPortSim) {
  const rig::Rig rig = load_rig_file(testing::write_temp_file("maestro_usb_rig_good.yaml", kUsbRig));
  EXPECT_EQ(rig.links[0].port, "");
  const rig::MaestroOptions options = rig.links[0].options_as<rig::MaestroOptions>();
  EXPECT_TRUE(options.usb);
  EXPECT_EQ(options.usb_serial, "00012345");
  EXPECT_EQ(options.channel_count, 6);
  const rig::Rig any =
      load_rig_file(testing::write_temp_file("maestro_usb_rig_any.yaml", replace(kUsbRig, "usb: \"00012345\"", "usb: any")));
  EXPECT_EQ(any.links[0].options_as<rig::MaestroOptions>().usb_serial, "");  // the only one present
  const rig::Rig sim = load_rig_file(
      testing::write_temp_file("maestro_usb_rig_sim.yaml", replace(kUsbRig, "head: {maestro", "head: {port: sim, maestro")));
  EXPECT_TRUE(sim.links[0].simulated());
}

TEST(MaestroUsbRig, RejectsEachBadEntryWithWhereAndWhat) {
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, "head: {maestro", "head: {port: /dev/ttyACM0, maestro")),
            ":3:60: link 'head' names both a port (/dev/ttyACM0) and usb: 00012345; expected one of them: usb finds the "
            "Maestro by its serial number (leave out the port, or write port: sim), a port opens its virtual serial port");
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, "\"00012345\"", "\"0001 2345\"")),
            ":3:40: expected usb: any (the only Maestro present) or the Maestro's serial number, letters and digits as "
            "lsusb -v shows it (such as \"00012345\"); found '0001 2345'");
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, "model: micro6,", "model: micro6, crc: true,")),
            ":3:40: crc is a setting of the Maestro's serial port; link 'head' reaches its Maestro on USB (usb: 00012345), "
            "where it does not apply: remove it, or remove usb");
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, "model: micro6,", "model: micro6, device_number: 12,")).substr(0, 60),
            ":3:50: device_number is a setting of the Maestro's serial po");
  // Without usb the port is needed, as ever.
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, ", usb: \"00012345\"", "")).substr(0, 20), ":3:9: missing field ");
  // The model's channels still bound the actuators.
  EXPECT_EQ(usb_rig_error(replace(kUsbRig, "device_channel: 5", "device_channel: 6")).substr(0, 40),
            ":7:67: expected device_channel from 0 to");
}

}  // namespace
}  // namespace avar::config
