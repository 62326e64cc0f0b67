// The Art-Net and sACN links against the simulated node over real loopback UDP: 8- and 16-bit
// slots arrive as commanded, sequence numbers count, bad packets of every kind are counted and
// leave the universe alone, and the node answers ArtPoll.
#include "avar/sim/sim_dmx_node.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <vector>

#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/firmware_iface/artnet_poll_codec.hpp"
#include "avar/firmware_iface/network_dmx_link.hpp"

namespace avar::sim {
namespace {

namespace fi = firmware_iface;
using std::chrono::milliseconds;

std::vector<fi::DmxActuator> node_test_actuators() {
  fi::DmxActuator dimmer;  // channel 0, 0..100 % -> 0..255
  dimmer.channel = 0;
  dimmer.address = 1;
  dimmer.calibration = {0, 100, 0, 255, false, 0};
  fi::DmxActuator pan;  // channel 1, -90..90 deg -> 0..65535 on slots 5 and 6
  pan.channel = 1;
  pan.address = 5;
  pan.fine = true;
  pan.calibration = {-90, 90, 0, 65535, false, 0};
  return {dimmer, pan};
}

fi::UdpDestination node_test_destination(const SimDmxNode& node) { return fi::parse_udp_destination(node.endpoint(), 1); }

TEST(SimDmxNodeLinks, ArtnetLinkDelivers8And16BitSlotsWithSequenceNumbers) {
  SimDmxNode node({DmxNodeProtocol::artnet, fi::artnet::port_address(0, 1, 2), 0, "node"});
  fi::ArtnetLinkConfig config;
  config.destination = node_test_destination(node);
  config.port_address = fi::artnet::port_address(0, 1, 2);
  config.actuators = node_test_actuators();
  fi::ArtnetLink link(config);
  EXPECT_EQ(link.slot_count(), 6U);
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 2> frame{50.0, 45.0};
  for (int i = 0; i < 3; ++i) ASSERT_EQ(link.send(frame), Status::ok);
  ASSERT_TRUE(node.receive_until(link.counters().bytes_sent, milliseconds(2000)));
  EXPECT_EQ(node.counters().packets, 3U);
  EXPECT_EQ(node.counters().bad_packets, 0U);
  EXPECT_EQ(link.last_sequence(), 3);
  EXPECT_EQ(node.slot_count(), 6U);
  EXPECT_EQ(node.slot(1), 128);           // 127.5 rounds up
  EXPECT_EQ(node.level(5, true), 49151);  // 135/180 of 65535, rounded
  EXPECT_EQ(link.counters().exchanges, 3U);
  EXPECT_EQ(link.counters().bytes_sent, 3U * fi::artnet::dmx_packet_size(6));

  // Beyond the calibration: saturated, counted.
  const std::array<double, 2> beyond{150.0, -120.0};
  ASSERT_EQ(link.send(beyond), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(frame), Status::ok);
  ASSERT_TRUE(node.receive_until(link.counters().bytes_sent, milliseconds(2000)));
  EXPECT_EQ(link.saturated_pulses(), 2U);
  EXPECT_EQ(node.slot(1), 128);
  EXPECT_EQ(node.level(5, true), 0);  // released: level 0
  ASSERT_EQ(link.release(), Status::ok);
  ASSERT_TRUE(node.receive_until(link.counters().bytes_sent, milliseconds(2000)));
  EXPECT_EQ(node.slot(1), 0);
}

TEST(SimDmxNodeLinks, ArtnetSequenceWrapsPast255Skipping0) {
  SimDmxNode node({DmxNodeProtocol::artnet, 0, 0, "node"});
  fi::ArtnetLinkConfig config;
  config.destination = node_test_destination(node);
  config.actuators = node_test_actuators();
  fi::ArtnetLink link(config);
  const std::array<double, 2> frame{10.0, 0.0};
  for (int i = 0; i < 256; ++i) ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(link.last_sequence(), 1);
  ASSERT_TRUE(node.receive_until(link.counters().bytes_sent, milliseconds(2000)));
  EXPECT_EQ(node.counters().out_of_order, 0U);
  EXPECT_EQ(node.counters().packets + link.counters().timeouts, 256U);
}

TEST(SimDmxNodeLinks, SacnLinkDeliversPriorityNameDiscoveryAndTerminates) {
  SimDmxNode node({DmxNodeProtocol::sacn, 7, 0, "node"});
  {
    fi::SacnLinkConfig config;
    config.destination = node_test_destination(node);
    config.universe = 7;
    config.priority = 150;
    config.source_name = "avar test";
    config.discovery_every = 4;
    config.actuators = node_test_actuators();
    fi::SacnLink link(config);
    const std::array<double, 2> frame{100.0, -90.0};
    for (int i = 0; i < 8; ++i) ASSERT_EQ(link.send(frame), Status::ok);
    EXPECT_EQ(link.discovery_packets(), 2U);
    ASSERT_TRUE(node.receive_until(link.counters().bytes_sent, milliseconds(2000)));
    EXPECT_EQ(node.counters().packets, 8U);
    EXPECT_EQ(node.counters().discovery, 2U);
    EXPECT_EQ(node.priority(), 150);
    EXPECT_EQ(node.source_name(), "avar test");
    EXPECT_EQ(node.slot(1), 255);
    EXPECT_EQ(node.level(5, true), 0);
  }
  // Destroyed: three stream-terminated packets, which do not change the levels.
  SimDmxNodeCounters before = node.counters();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (node.counters().terminated < 3 && std::chrono::steady_clock::now() < deadline)
    node.receive_until(before.bytes + 1, milliseconds(100));
  EXPECT_EQ(node.counters().terminated, 3U);
  EXPECT_EQ(node.slot(1), 255);
}

TEST(SimDmxNodeLinks, BadPacketsOfEveryKindAreCountedAndChangeNothing) {
  SimDmxNode node({DmxNodeProtocol::artnet, 3, 0, "node"});
  std::array<std::uint8_t, fi::artnet::kMaxDmxPacketSize> good{};
  const std::array<std::uint8_t, 4> slots{10, 20, 30, 40};
  const std::size_t n = fi::artnet::encode_dmx(good, 5, 0, 3, slots);
  node.handle(std::span(good.data(), n));
  ASSERT_EQ(node.counters().packets, 1U);
  std::uint64_t bad = 0;
  // Every truncation, every corruption of a header byte, random garbage, an sACN packet.
  for (std::size_t len = 0; len < n; ++len, ++bad) node.handle(std::span(good.data(), len));
  // ID, ID terminator, an unknown OpCode, version 13, Net bit 7, odd length.
  const std::array<std::pair<std::size_t, std::uint8_t>, 6> corruptions{
      {{0, 'a'}, {7, '!'}, {9, 0x51}, {11, 13}, {15, 0x80}, {17, 0x03}}};
  for (const auto& [at, value] : corruptions) {
    auto corrupt = good;
    corrupt[at] = value;
    node.handle(std::span(corrupt.data(), n));
    ++bad;
  }
  std::uint32_t state = 12345;
  for (int i = 0; i < 200; ++i, ++bad) {
    std::vector<std::uint8_t> garbage(1 + (state % 600));
    for (auto& b : garbage) b = static_cast<std::uint8_t>((state = state * 1664525U + 1013904223U) >> 24U);
    node.handle(garbage);
  }
  EXPECT_EQ(node.counters().bad_packets, bad);
  // Another universe, and a stale sequence number: counted apart, ignored.
  std::array<std::uint8_t, fi::artnet::kMaxDmxPacketSize> other{};
  const std::array<std::uint8_t, 4> zeros{};
  node.handle(std::span(other.data(), fi::artnet::encode_dmx(other, 6, 0, 4, zeros)));
  node.handle(std::span(other.data(), fi::artnet::encode_dmx(other, 4, 0, 3, zeros)));
  EXPECT_EQ(node.counters().other_universe, 1U);
  EXPECT_EQ(node.counters().out_of_order, 1U);
  EXPECT_EQ(node.counters().packets, 1U);
  for (int s = 1; s <= 4; ++s) EXPECT_EQ(node.slot(s), slots[static_cast<std::size_t>(s - 1)]);
}

TEST(SimDmxNodeLinks, AnswersArtPollWithAPollReplyNamingItsPort) {
  SimDmxNode node({DmxNodeProtocol::artnet, fi::artnet::port_address(1, 2, 3), 0, "sim node"});
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in self{};
  self.sin_family = AF_INET;
  self.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&self), sizeof self), 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(node.port());
  std::array<std::uint8_t, fi::artnet::kPollSize> poll{};
  const std::size_t n = fi::artnet::encode_poll(poll, fi::artnet::Poll{});
  ASSERT_EQ(::sendto(fd, poll.data(), n, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to), static_cast<ssize_t>(n));
  ASSERT_TRUE(node.receive_until(n, milliseconds(2000)));
  EXPECT_EQ(node.counters().polls_answered, 1U);
  pollfd p{fd, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1);
  std::array<std::uint8_t, 512> reply{};
  const ssize_t got = ::recv(fd, reply.data(), reply.size(), 0);
  ::close(fd);
  ASSERT_EQ(got, static_cast<ssize_t>(fi::artnet::kPollReplySize));
  const auto r = fi::artnet::decode_poll_reply(std::span(reply.data(), static_cast<std::size_t>(got)));
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->short_name.view(), "sim node");
  EXPECT_EQ(r->num_ports, 1);
  EXPECT_EQ(r->output_port_address(0), fi::artnet::port_address(1, 2, 3));
}

}  // namespace
}  // namespace avar::sim
