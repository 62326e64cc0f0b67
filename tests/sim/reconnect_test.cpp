// Every driver survives its port going away and coming back: sends fail with io_error while the
// wire is unplugged, and the port is reopened (a bounded number of sends later) once it returns.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <vector>

#include "avar/firmware_iface/dmx_link.hpp"
#include "avar/firmware_iface/maestro_codec.hpp"
#include "avar/firmware_iface/maestro_link.hpp"
#include "avar/firmware_iface/ssc32_link.hpp"
#include "avar/sim/sim_dmx.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/sim/sim_ssc32.hpp"
#include "avar/sim/sim_wire.hpp"

namespace avar::sim {
namespace {

namespace fw = firmware_iface;

void unplug_and_replug(fw::ActuatorLink& link, SimWire& wire, const char* what) {
  SCOPED_TRACE(what);
  const std::vector<double> frame{0.5, 0.25};
  ASSERT_EQ(link.start(), Status::ok);
  ASSERT_EQ(link.send(frame), Status::ok);
  // A write-only link counts its sends and their bytes; a send the wire did not take is not one.
  const fw::LinkCounters first = link.counters();
  EXPECT_EQ(first.exchanges, 1u);
  EXPECT_GT(first.bytes_sent, 0u);
  wire.set_connected(false);
  for (int i = 0; i < 25; ++i) EXPECT_EQ(link.send(frame), Status::io_error);
  EXPECT_EQ(link.counters().reconnects, 0u);
  EXPECT_EQ(link.counters().exchanges, 1u);
  EXPECT_EQ(link.counters().bytes_sent, first.bytes_sent);
  wire.set_connected(true);
  Status s = Status::io_error;
  int sends = 0;
  for (; sends < 20 && s != Status::ok; ++sends) s = link.send(frame);
  EXPECT_EQ(s, Status::ok);
  EXPECT_LE(sends, 10);  // reconnect_every
  EXPECT_EQ(link.counters().reconnects, 1u);
  EXPECT_EQ(link.counters().exchanges, 2u);
  EXPECT_EQ(link.counters().bytes_sent, 2 * first.bytes_sent);
  EXPECT_EQ(wire.reopens(), 1u);
}

TEST(Reconnect, MaestroSsc32AndDmxLinksReopenTheirPortWhenItComesBack) {
  {
    SimMaestroConfig dc;
    dc.channel_count = 12;
    SimMaestro device(dc);
    SimWire wire(device, 115200);
    fw::MaestroLinkConfig c;
    c.channel_count = 12;
    c.actuators.push_back({0, 0, {0, 1, 1000, 2000, false, 0}, {}, {}});
    c.actuators.push_back({1, 1, {0, 1, 1000, 2000, false, 0}, {}, {}});
    fw::MaestroLink link(wire, c);
    unplug_and_replug(link, wire, "maestro");
  }
  {
    SimSsc32 device({});
    SimWire wire(device, 115200);
    fw::Ssc32LinkConfig c;
    c.actuators.push_back({0, 0, {0, 1, 1000, 2000, false, 0}, {}});
    c.actuators.push_back({1, 5, {0, 1, 1000, 2000, false, 0}, {}});
    fw::Ssc32Link link(wire, c);
    unplug_and_replug(link, wire, "ssc32");
  }
  {
    SimDmx device({});
    SimWire wire(device, 115200);
    fw::DmxLinkConfig c;
    c.actuators.push_back({0, 1, false, {0, 1, 0, 255, false, 0}});
    c.actuators.push_back({1, 2, true, {0, 1, 0, 65535, false, 0}});
    fw::DmxLink link(wire, c);
    unplug_and_replug(link, wire, "dmx");
  }
}

TEST(Reconnect, AMaestroThatCameBackGetsItsSpeedAndAccelerationLimitsAgain) {
  // Unplugged, a Maestro restarts with its saved settings: the link's limits must be sent again.
  SimMaestroConfig dc;
  dc.channel_count = 12;
  dc.log_limit = 10000;
  SimMaestro device(dc);
  SimWire wire(device, 115200);
  fw::MaestroLinkConfig c;
  c.channel_count = 12;
  c.actuators.push_back({0, 3, {0, 1, 1000, 2000, false, 0}, 500.0, 2500.0});
  fw::MaestroLink link(wire, c);
  const auto count = [&](std::uint8_t command) {
    return std::count_if(device.log().begin(), device.log().end(), [&](const MaestroCommand& m) { return m.command == command; });
  };
  const std::vector<double> frame{0.5};
  ASSERT_EQ(link.start(), Status::ok);
  EXPECT_EQ(count(fw::maestro::kSetSpeed), 1);
  EXPECT_EQ(count(fw::maestro::kSetAcceleration), 1);
  wire.set_connected(false);
  EXPECT_EQ(link.send(frame), Status::io_error);
  wire.set_connected(true);
  Status s = Status::io_error;
  for (int i = 0; i < 20 && s != Status::ok; ++i) s = link.send(frame);
  ASSERT_EQ(s, Status::ok);
  EXPECT_EQ(count(fw::maestro::kSetSpeed), 2);
  EXPECT_EQ(count(fw::maestro::kSetAcceleration), 2);
  EXPECT_EQ(device.log().back().command, fw::maestro::kSetTarget);  // the limits first, then the frame
  EXPECT_EQ(device.speed(3), 20);                                   // 500 µs/s in units of 25 µs/s
}

}  // namespace
}  // namespace avar::sim
