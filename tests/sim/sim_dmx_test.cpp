// The simulated DMX USB Pro keeps the universe it is sent and answers the widget requests;
// DmxLink drives 8- and 16-bit actuators through it in memory and through a pseudo-terminal.
#include "avar/sim/sim_dmx.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "avar/firmware_iface/dmx_link.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/sim_wire.hpp"
#include "avar/sim/pty_device_host.hpp"

namespace avar::sim {
namespace {

namespace fw = firmware_iface;
namespace dmx = firmware_iface::dmx;
using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

Bytes replies(SimDmx& d) {
  std::array<std::uint8_t, 700> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

Bytes e3() {
  Bytes m{0x7E, 0x06, 0x19, 0x00, 0x00, 0xFF, 0x80};
  m.resize(5 + 24, 0);
  m.push_back(0xE7);
  return m;
}

TEST(SimDmx, E3_KeepsTheUniverseAndDoesNotAnswer) {
  SimDmx d({});
  d.receive(e3());
  EXPECT_TRUE(replies(d).empty());
  EXPECT_EQ(d.slot(1), 255);
  EXPECT_EQ(d.slot(2), 128);
  EXPECT_EQ(d.slot(3), 0);
  EXPECT_EQ(d.slot_count(), 24u);
  EXPECT_EQ(d.frames_received(), 1u);
}

TEST(SimDmx, E4_AnswersGetWidgetParametersAndTakesNewOnes) {
  SimDmx d({});
  d.receive(Bytes{0x7E, 0x03, 0x02, 0x00, 0x00, 0x00, 0xE7});
  EXPECT_EQ(replies(d), (Bytes{0x7E, 0x03, 0x05, 0x00, 0x44, 0x01, 0x09, 0x01, 0x28, 0xE7}));
  d.receive(Bytes{0x7E, 0x04, 0x05, 0x00, 0x00, 0x00, 0x14, 0x02, 0x00, 0xE7});  // break 20, MAB 2, rate max
  EXPECT_TRUE(replies(d).empty());
  EXPECT_EQ(d.parameters().break_time, 20);
  EXPECT_EQ(d.parameters().output_rate, 0);
  d.receive(Bytes{0x7E, 0x04, 0x05, 0x00, 0x00, 0x00, 0x05, 0x02, 0x00, 0xE7});  // break 5: out of range
  EXPECT_EQ(d.parameters().break_time, 20);
  d.receive(Bytes{0x7E, 0x03, 0x02, 0x00, 0x03, 0x00, 0xE7});  // with 3 user-configuration bytes
  EXPECT_EQ(replies(d).size(), 5u + 5 + 3);
}

TEST(SimDmx, E5_AnswersTheSerialNumber) {
  SimDmx d({});
  d.receive(Bytes{0x7E, 0x0A, 0x00, 0x00, 0xE7});
  EXPECT_EQ(replies(d), (Bytes{0x7E, 0x0A, 0x04, 0x00, 0x78, 0x56, 0x34, 0x12, 0xE7}));
}

TEST(SimDmx, SkipsNoiseAndRefusesShortUniverses) {
  SimDmx d({});
  Bytes stream{0x00, 0x42};
  const Bytes good = e3();
  stream.insert(stream.end(), good.begin(), good.end());
  d.receive(std::span(stream).first(10));
  d.receive(std::span(stream).subspan(10));
  EXPECT_EQ(d.framing_errors(), 2u);
  EXPECT_EQ(d.slot(1), 255);
  d.receive(Bytes{0x7E, 0x06, 0x03, 0x00, 0x00, 0x01, 0x02, 0xE7});  // 2 slots: below 24
  EXPECT_EQ(d.slot(1), 255);
  EXPECT_EQ(d.frames_received(), 1u);
}

TEST(SimDmx, PacketsGoOutAtTheOutputRateAndFixturesFollow) {
  SimDmxConfig c;
  c.fixtures = {{1, false, 1000, 2000, 1500}, {3, true, 1000, 2000, 1500}};
  SimDmx d(c);
  Bytes slots(24, 0);
  slots[0] = 255, slots[2] = 0x40, slots[3] = 0x00;  // fixture 2 at 0x4000 / 0xFFFF
  std::array<std::uint8_t, dmx::kMaxMessageSize> m{};
  d.receive(std::span(m.data(), dmx::encode_send_dmx(m, slots)));
  d.advance(1.0);
  EXPECT_EQ(d.dmx_packets_sent(), 40u);  // 40 packets/s
  EXPECT_EQ(d.fixture_level(1), 0x4000);
  EXPECT_NEAR(d.fixture_pulse_us(1), 1000 + 1000 * 0x4000 / 65535.0, 1e-9);
  EXPECT_NEAR(d.servo_position_us(0), 2000, 3);
  EXPECT_NEAR(d.servo_position_us(1), 1250, 3);
  EXPECT_DOUBLE_EQ(d.dmx_period(), 1.0 / 40);
  EXPECT_DOUBLE_EQ(d.wire_time(dmx::send_dmx_size(24)), 30 * 10 / 115200.0);
  SimDmxConfig bad;
  bad.fixtures = {{512, true, 1000, 2000, 1500}};
  EXPECT_THROW(SimDmx{bad}, std::invalid_argument);
}

fw::DmxLinkConfig dmx_link_config() {
  fw::DmxLinkConfig c;
  c.actuators.push_back({0, 1, false, {-90, 90, 0, 255, false, 0}});
  c.actuators.push_back({1, 3, true, {-90, 90, 0, 65535, false, 0}});
  c.actuators.push_back({2, 30, false, {0, 100, 0, 255, true, 0}});
  return c;
}

TEST(DmxLink, EachTickSendsTheWholeUniverseOnce) {
  SimDmxConfig c;
  c.fixtures = {{1, false, 1000, 2000, 1500}, {3, true, 1000, 2000, 1500}};
  SimDmx widget(c);
  SimWire t(widget);
  fw::DmxLink link(t, dmx_link_config());
  ASSERT_EQ(link.start(), Status::ok);
  EXPECT_EQ(link.widget_parameters().output_rate, 40);
  EXPECT_EQ(link.slot_count(), 30u);
  const std::uint64_t writes = t.writes();
  ASSERT_EQ(link.send(std::array<double, 3>{90, 0, 25}), Status::ok);
  EXPECT_EQ(t.writes(), writes + 1);
  EXPECT_EQ(link.last_send_size(), dmx::send_dmx_size(30));
  EXPECT_EQ(widget.slot(1), 255);
  EXPECT_EQ(widget.fixture_level(1), 32768);  // 0 ° = middle of 0..65535, rounded
  EXPECT_EQ(widget.slot(3), 0x80);
  EXPECT_EQ(widget.slot(4), 0x00);
  EXPECT_EQ(widget.slot(30), 191);  // reversed: 25 % -> 75 % of 255
  EXPECT_EQ(widget.slot_count(), 30u);
  ASSERT_EQ(link.send(std::array<double, 3>{-90, -45, 200}), Status::ok);
  EXPECT_EQ(widget.slot(1), 0);
  EXPECT_EQ(widget.fixture_level(1), 16384);
  EXPECT_EQ(widget.slot(30), 0);  // saturated at the end of the window
  EXPECT_EQ(link.saturated_pulses(), 1u);
  std::array<double, 3> frame{7, 7, 7};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(frame, known), Status::ok);
  EXPECT_FALSE(known[0] || known[1] || known[2]);
  EXPECT_EQ(frame[0], 7);
}

TEST(DmxLink, ReleaseSendsLevelZero) {
  SimDmx widget({});
  SimWire t(widget);
  fw::DmxLink link(t, dmx_link_config());
  ASSERT_EQ(link.send(std::array<double, 3>{90, 90, 0}), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(std::array<double, 3>{90, 90, 0}), Status::ok);
  EXPECT_EQ(widget.slot(1), 255);
  EXPECT_EQ(widget.slot(3), 0);
  EXPECT_EQ(widget.slot(4), 0);
  ASSERT_EQ(link.release(), Status::ok);
  EXPECT_EQ(widget.slot(1), 0);
  EXPECT_EQ(widget.slot(30), 0);
}

TEST(DmxLink, RefusesSlotsThatDoNotFitOrOverlap) {
  SimDmx widget({});
  SimWire t(widget);
  fw::DmxLinkConfig overlap = dmx_link_config();
  overlap.actuators[2].address = 4;  // inside the 16-bit pair 3-4
  EXPECT_THROW(fw::DmxLink(t, overlap), std::invalid_argument);
  fw::DmxLinkConfig outside = dmx_link_config();
  outside.actuators[1].address = 512;  // fine needs 513
  EXPECT_THROW(fw::DmxLink(t, outside), std::invalid_argument);
  fw::DmxLinkConfig short_count = dmx_link_config();
  short_count.slot_count = 10;
  EXPECT_THROW(fw::DmxLink(t, short_count), std::invalid_argument);
  fw::DmxLinkConfig full = dmx_link_config();
  full.slot_count = 512;
  EXPECT_EQ(fw::DmxLink(t, full).slot_count(), 512u);
}

TEST(DmxLink, EndToEndThroughTheSerialTransportAndAPseudoTerminal) {
  SimDmxConfig c;
  c.fixtures = {{1, false, 1000, 2000, 1500}, {3, true, 1000, 2000, 1500}};
  SimDmx widget(c);
  PtyDeviceHost host(widget, PtyDeviceHost::Clock::stepped);
  fw::SerialTransport port(host.slave_path(), 115200);
  fw::DmxLinkConfig config = dmx_link_config();
  config.reply_timeout = 2000ms;
  fw::DmxLink link(port, config);
  ASSERT_EQ(link.start(), Status::ok);
  for (int tick = 1; tick <= 50; ++tick) {
    const double s = std::min(1.0, tick / 30.0);
    ASSERT_EQ(link.send(std::array<double, 3>{45 * s, -45 * s, 0}), Status::ok);
    ASSERT_TRUE(host.wait_consumed(port.bytes_written(), 2000ms));
    host.with_device([](ByteDevice& d) { d.advance(0.025); });
  }
  host.with_device([](ByteDevice& d) {
    auto& w = static_cast<SimDmx&>(d);
    EXPECT_EQ(w.frames_received(), 50u);
    EXPECT_EQ(w.slot(1), 191);  // 45 of ±90 over 0..255
    EXPECT_EQ(w.fixture_level(1), 16384);
    EXPECT_NEAR(w.servo_position_us(0), 1750, 3);
    EXPECT_NEAR(w.servo_position_us(1), 1250, 3);
    return 0;
  });
}

}  // namespace
}  // namespace avar::sim
