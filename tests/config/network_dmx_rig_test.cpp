// Rig files with artnet and sacn links: their settings read into the drivers' configurations, and
// every bad setting named with file:line:col and what was expected.

#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "avar/assembly/network_dmx_protocol.hpp"
#include "avar/config/rig_file.hpp"

namespace avar::config {
namespace {

const char* kNetworkRig = R"(name: stage
rate_hz: 40
links:
  art: {artnet: {to: 10.0.0.20, net: 1, subnet: 2, universe: 3, slots: 64}}
  acn: {sacn: {universe: 7, priority: 150, cid: 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f, preview: true}}
channels:
  dim: {unit: '%', min: 0, max: 100, rest: 0, max_velocity: 100}
  pan: {unit: deg, min: -90, max: 90, rest: 0, max_velocity: 90}
actuators:
  - {channel: dim, link: art, address: 1}
  - {channel: pan, link: acn, address: 511, fine: true}
)";

std::string network_rig_error(const std::string& from, const std::string& to) {
  return avar::testing::load_error(load_rig_file, avar::testing::replace(kNetworkRig, from, to), "network_rig.yaml");
}

TEST(NetworkDmxRig, ReadsArtnetAndSacnSettings) {
  const rig::Rig rig = load_rig_file(testing::write_temp_file("network_rig.yaml", kNetworkRig));
  ASSERT_EQ(rig.links.size(), 2U);
  EXPECT_EQ(rig.links[0].protocol, "artnet");
  EXPECT_EQ(rig.links[0].port, "");
  const firmware_iface::ArtnetLinkConfig art = assembly::artnet_config(rig, 0, "");
  EXPECT_EQ(art.destination.host, "10.0.0.20");
  EXPECT_EQ(art.destination.port, 6454);
  EXPECT_FALSE(art.destination.broadcast);
  EXPECT_EQ(art.port_address, 0x0123);
  EXPECT_EQ(art.slot_count, 64U);
  ASSERT_EQ(art.actuators.size(), 1U);
  EXPECT_EQ(assembly::artnet_config(rig, 0, "127.0.0.1:7000").destination.port, 7000);

  const firmware_iface::SacnLinkConfig acn = assembly::sacn_config(rig, 1, "");
  EXPECT_EQ(acn.destination.host, "");  // the universe's multicast group
  EXPECT_EQ(acn.universe, 7);
  EXPECT_EQ(acn.priority, 150);
  EXPECT_TRUE(acn.preview);
  EXPECT_EQ(acn.cid[0], 0x6f);
  EXPECT_EQ(acn.cid[15], 0x6f);
  EXPECT_EQ(acn.discovery_every, 400U);  // 10 s at 40 Hz
  EXPECT_EQ(acn.source_name, "avar stage acn");
  ASSERT_EQ(acn.actuators.size(), 1U);
  EXPECT_TRUE(acn.actuators[0].fine);
  // The derived CID stays the same from run to run.
  const rig::Rig again = load_rig_file(testing::write_temp_file(
      "network_rig2.yaml", avar::testing::replace(kNetworkRig, ", cid: 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f", "")));
  EXPECT_EQ(assembly::sacn_config(again, 1, "").cid, assembly::sacn_config(again, 1, "").cid);
  EXPECT_EQ(assembly::sacn_config(again, 1, "").cid[6] >> 4, 5);
}

TEST(NetworkDmxRig, NamesEveryBadSettingWhereItStands) {
  EXPECT_EQ(network_rig_error("to: 10.0.0.20, ", ""),
            ":4:17: expected `to: NODE_IP` in the artnet settings of link 'art': Art-Net goes to a stated node (broadcast only "
            "with `to: 2.255.255.255, broadcast: true`)");
  EXPECT_EQ(network_rig_error("to: 10.0.0.20", "to: lights.local"),
            ":4:22: expected the destination to be a numeric IPv4 address such as 10.0.0.20, found 'lights.local'");
  EXPECT_EQ(network_rig_error("to: 10.0.0.20", "to: 10.0.0.20:0"),
            ":4:22: expected a UDP port from 1 to 65535 after the ':' of '10.0.0.20:0'");
  EXPECT_EQ(network_rig_error("to: 10.0.0.20", "to: 10.0.0.255"),
            ":4:22: expected a node's address; '10.0.0.255' looks like a broadcast address: add broadcast: true to send to "
            "every node");
  EXPECT_EQ(network_rig_error("to: 10.0.0.20", "to: 10.0.0.255, broadcast: true"), "");
  EXPECT_EQ(network_rig_error("net: 1", "net: 128"), ":4:38: expected net from 0 to 127, found '128'");
  EXPECT_EQ(network_rig_error("subnet: 2", "subnet: 16"), ":4:49: expected subnet from 0 to 15, found '16'");
  EXPECT_EQ(network_rig_error("slots: 64", "slots: 513"), ":4:72: expected slots from 1 to 512, found '513'");
  EXPECT_EQ(network_rig_error("universe: 7", "universe: 64000"), ":5:26: expected universe from 1 to 63999, found '64000'");
  EXPECT_EQ(network_rig_error("universe: 7, ", ""), ":5:15: expected `universe: 1..63999` in the sacn settings of link 'acn'");
  EXPECT_EQ(network_rig_error("priority: 150", "priority: 201"), ":5:39: expected priority from 0 to 200, found '201'");
  EXPECT_EQ(network_rig_error("cid: 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f", "cid: 6f3b2a10"),
            ":5:49: expected cid to be a UUID such as 6f3b2a10-94c1-4e0b-9d8e-1a2b3c4d5e6f, found '6f3b2a10'");
  EXPECT_EQ(network_rig_error("preview: true", "colour: red"),
            ":5:87: unknown field 'colour' in the sacn settings of link 'acn'; expected one of: to, universe, priority, "
            "source_name, cid, preview, multicast_ttl, multicast_interface, discovery, slots");
  EXPECT_EQ(network_rig_error("address: 511, fine: true", "address: 512, fine: true"),
            ":11:40: expected address from 1 to 511 on sacn link 'acn', found '512'");
}

}  // namespace
}  // namespace avar::config
