// CAN links in rig files: the drives' keys, node ranges, bitrates, models and bus identifiers are
// checked whole at load, each error at its file:line:column; a good CAN rig maps each channel to
// its motor by gear ratio, units per turn and zero.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/input_errors.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

std::string can_rig_error(const std::string& text) { return avar::testing::load_error(load_rig_file, text, "can_rig.yaml"); }
using avar::testing::replace;

const char* kCanRig = R"(name: bus
links:
  arm: {port: sim, can: {bitrate: 1000000, mit_master_id: 0x7F0}}
channels:
  base: {unit: deg, min: -90, max: 90, rest: 0}
  lift: {unit: mm, min: 0, max: 200, rest: 0}
  jaw: {unit: deg, min: 0, max: 30, rest: 0}
actuators:
  - {channel: base, link: arm, protocol: odrive, node: 1, gear_ratio: 8}
  - {channel: lift, link: arm, protocol: cia402, node: 5, units_per_turn: 8, counts_per_turn: 10000, zero: 100}
  - {channel: jaw, link: arm, protocol: mit, node: 100, gear_ratio: 6, reverse: true, model: mini-cheetah, kp: 30, kd: 1}
)";

TEST(CanRig, LoadsDrivesAndMapsChannelsToTheirMotors) {
  const rig::Rig rig = load_rig_file(testing::write_temp_file("can_rig_good.yaml", kCanRig));
  ASSERT_EQ(rig.actuators.size(), 3u);
  EXPECT_EQ(rig.actuators[0].drive, "odrive");
  EXPECT_EQ(rig.actuators[1].drive, "cia402");
  EXPECT_EQ(rig.actuators[2].drive, "mit");
  // 90° at the joint through 8:1 is 2 motor turns.
  EXPECT_NEAR(rig.actuators[0].calibration.to_device(90), 2.0, 1e-12);
  // 8 mm per turn, zero at 100 mm: 200 mm is 12.5 turns = 125000 counts; 0 mm is -125000.
  EXPECT_NEAR(rig.actuators[1].calibration.to_device(200), 125000, 1e-6);
  EXPECT_NEAR(rig.actuators[1].calibration.to_device(0), -125000, 1e-6);
  // Reversed: 30° through 6:1 is -π rad.
  EXPECT_NEAR(rig.actuators[2].calibration.to_device(30), -std::numbers::pi, 1e-12);
}

TEST(CanRig, RejectsEachBadEntryWithWhereAndWhat) {
  EXPECT_EQ(can_rig_error(replace(kCanRig, "protocol: odrive, ", "")),
            ":9:5: expected the drive protocol of an actuator on CAN link 'arm': protocol: odrive, cia402, mit");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "protocol: odrive", "protocol: odrv")),
            ":9:42: unknown CAN drive protocol 'odrv'; expected one of: odrive, cia402, mit");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "node: 1, gear_ratio: 8", "node: 64, gear_ratio: 8")),
            ":9:56: expected the node id of an ODrive from 0 to 63, found '64'");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "node: 5,", "node: 0,")),
            ":10:56: expected the node id of a CiA 402 drive from 1 to 127, found '0'");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "counts_per_turn: 10000, ", "")).substr(0, 60),
            ":10:5: expected counts_per_turn for the CiA 402 drive at nod");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "model: mini-cheetah", "model: ak80"))
                .rfind(":11:94: unknown MIT motor model 'ak80'; expected one of: mini-cheetah", 0),
            0u);
  EXPECT_EQ(can_rig_error(replace(kCanRig, "kp: 30", "kp: 600")),
            ":11:112: expected kp (at most the model's kp_max) from 0 to 500 N·m/rad, found '600'");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "gear_ratio: 8}", "gear_ratio: 8, current_limit: 10, speed_khz: 1}")),
            ":9:93: unknown field 'speed_khz' in the settings of actuator 1; expected one of: protocol, node, gear_ratio, "
            "units_per_turn, zero, reverse, current_limit, input_mode");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "bitrate: 1000000", "bitrate: 750000")),
            ":3:35: expected a CAN bitrate in bit/s, one of: 10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000, "
            "1000000; found '750000'");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "bitrate: 1000000", "bitrate: 800000")),
            ":9:56: an ODrive cannot run at the 800000 bit/s of link 'arm'; expected one of: 125000, 250000, 500000, 1000000");
  EXPECT_EQ(can_rig_error(replace(kCanRig, "gear_ratio: 8}", "gear_ratio: 8, calibration: {min_us: 1}}")).substr(0, 52),
            ":9:87: actuators on can link 'arm' take no calibrati");
  // A channel in mm needs units_per_turn.
  EXPECT_EQ(can_rig_error(replace(kCanRig, "units_per_turn: 8, ", "")).substr(0, 70),
            ":10:5: channel 'lift' is in 'mm', which does not say how far one outpu");
  // The jaw's 30° through 60:1 is 31 rad, beyond the model's ±12.5.
  EXPECT_EQ(can_rig_error(replace(kCanRig, "gear_ratio: 6", "gear_ratio: 60")).substr(0, 60),
            ":11:5: the channel's range takes this MIT motor from -31.415");
}

TEST(CanRig, RejectsDrivesWhoseIdentifiersCollideOnOneBus) {
  // ODrive node 3 uses 0x060..0x07F; an MIT motor at node 0x65 collides.
  const std::string node3 = replace(kCanRig, "node: 1, gear_ratio: 8", "node: 3, gear_ratio: 8");
  EXPECT_EQ(can_rig_error(replace(node3, "node: 100", "node: 0x65")),
            ":11:52: MIT motor node 101 uses CAN id 0x065, which the ODrive at node 3 (line 9) also uses on link 'arm'; "
            "expected a node whose identifiers are free");
  // MIT motors reply to id 0 by default, CANopen's NMT id: with CiA 402 drives the bus needs mit_master_id.
  EXPECT_EQ(can_rig_error(replace(kCanRig, ", mit_master_id: 0x7F0", "")),
            ":11:52: MIT motor node 100 uses CAN id 0x000, which the CiA 402 drive at node 5 (line 10) also uses on link 'arm'; "
            "expected a node whose identifiers are free");
  // Two CiA 402 drives share NMT and SYNC without conflict, but not a node.
  const std::string two = replace(kCanRig, "  - {channel: jaw, link: arm, protocol: mit",
                                  "  - {channel: jaw, link: arm, protocol: cia402, node: 5, counts_per_turn: 100}\n  - {channel: "
                                  "jaw, link: arm, protocol: mit");
  EXPECT_NE(can_rig_error(two).find("CiA 402 drive node 5 uses CAN id 0x085, which the CiA 402 drive at node 5 (line 10)"),
            std::string::npos)
      << can_rig_error(two);
}

}  // namespace
}  // namespace avar::config
