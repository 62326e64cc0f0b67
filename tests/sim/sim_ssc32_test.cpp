// The simulated SSC-32U answers the manual's queries byte for byte and times group moves as the
// board does; Ssc32Link drives it in memory and through a pseudo-terminal.
#include "avar/sim/sim_ssc32.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/firmware_iface/ssc32_link.hpp"
#include "avar/sim/sim_wire.hpp"
#include "avar/sim/pty_device_host.hpp"

namespace avar::sim {
namespace {

namespace fw = firmware_iface;
using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

void say(SimSsc32& d, const std::string& text) { d.receive(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())); }

Bytes replies(SimSsc32& d) {
  std::array<std::uint8_t, 64> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

TEST(SimSsc32, S3_S4_QueriesAnswerRawBytes) {
  SimSsc32 d({});
  say(d, "#5P1500\r");
  d.receive(Bytes{0x51, 0x50, 0x35, 0x0D});  // QP 5
  EXPECT_EQ(replies(d), Bytes{0x96});
  d.receive(Bytes{0x51, 0x0D});  // Q
  EXPECT_EQ(replies(d), Bytes{0x2E});
  say(d, "QP 5 QP 6\r");  // channel 6 outputs no pulse
  EXPECT_EQ(replies(d), (Bytes{0x96, 0x00}));
}

TEST(SimSsc32, AGroupMoveBringsEveryServoInTogether) {
  SimSsc32 d({});
  say(d, "#5P1000#6P2000\r");  // first moves jump
  EXPECT_EQ(d.output_pulse(5), 1000);
  say(d, "#5 P2000 #6 P1000 T1000 \r");
  d.advance(0.5);
  EXPECT_NEAR(d.output_pulse(5), 1500, 1e-6);
  EXPECT_NEAR(d.output_pulse(6), 1500, 1e-6);
  say(d, "Q\r");
  EXPECT_EQ(replies(d), Bytes{'+'});
  d.advance(0.5);
  EXPECT_EQ(d.output_pulse(5), 2000);
  say(d, "Q\r");
  EXPECT_EQ(replies(d), Bytes{'.'});
  d.advance(0.5);
  EXPECT_NEAR(d.servo_position_us(5), 2000, 3);  // the servo followed
}

TEST(SimSsc32, TheSlowestServoSetsTheGroupsTime) {
  SimSsc32 d({});
  say(d, "#5P1000#6P1000\r");
  say(d, "#5P2000S500#6P1500T1000\r");  // ch 5 needs 2 s at 500 µs/s
  d.advance(1.0);
  EXPECT_NEAR(d.output_pulse(5), 1500, 1e-6);
  EXPECT_NEAR(d.output_pulse(6), 1250, 1e-6);
  d.advance(1.0);
  EXPECT_EQ(d.output_pulse(6), 1500);
}

TEST(SimSsc32, LinesAreTakenOnlyWhenWholeAndValid) {
  SimSsc32 d({});
  say(d, "#5P12");
  say(d, "00\r");  // split across reads
  EXPECT_EQ(d.output_pulse(5), 1200);
  say(d, "#5P1800\x1b#5P1300\r");  // ESC drops what came before
  EXPECT_EQ(d.output_pulse(5), 1300);
  say(d, "#5P1800#6PO10\r");  // kinds mixed: ignored
  say(d, "#5P3000\r");        // out of range: ignored
  EXPECT_EQ(d.output_pulse(5), 1300);
  say(d, "#5p1400\r");
  EXPECT_EQ(d.output_pulse(5), 1400);
  say(d, std::string(600, '#') + "\r#5P1500\r");  // an overlong line is dropped whole
  EXPECT_EQ(d.output_pulse(5), 1500);
}

TEST(SimSsc32, OffsetsMoveTheServoNotTheReportedPulse) {
  SimSsc32 d({});
  say(d, "#2PO-50\r#2P1500\r");
  d.advance(1.0);
  EXPECT_NEAR(d.servo_position_us(2), 1450, 3);
  say(d, "QP2\r");
  EXPECT_EQ(replies(d), Bytes{150});
}

TEST(SimSsc32, AnOutputHeldLowSendsNoPulses) {
  SimSsc32 d({});
  say(d, "#4P1700\r");
  d.advance(1.0);
  say(d, "#4L\r");
  say(d, "QP4\r");
  EXPECT_EQ(replies(d), Bytes{0});
  const double where = d.servo_position_us(4);
  d.advance(1.0);
  EXPECT_EQ(d.servo_position_us(4), where);  // limp
}

TEST(SimSsc32, ModelsItsLineRate) {
  SimSsc32 d({});
  EXPECT_DOUBLE_EQ(d.wire_time(119), 119 * 10 / 115200.0);
  SimSsc32Config bad;
  bad.baud = 57600;
  EXPECT_THROW(SimSsc32{bad}, std::invalid_argument);
}

std::string text(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

fw::Ssc32LinkConfig ssc32_link_config() {
  fw::Ssc32LinkConfig c;
  c.actuators.push_back({0, 0, {-90, 90, 1000, 2000, false, 0}, {}});
  c.actuators.push_back({1, 7, {-90, 90, 1000, 2000, true, 0}, {}});
  c.actuators.push_back({2, 31, {0, 100, 900, 2100, false, 0}, 4000.0});
  return c;
}

TEST(Ssc32Link, EachTickIsOneGroupMoveTimedToTheTick) {
  SimSsc32 board({});
  SimWire t(board);
  fw::Ssc32Link link(t, ssc32_link_config());
  ASSERT_EQ(link.start(), Status::ok);
  const std::uint64_t writes = t.writes();
  ASSERT_EQ(link.send(std::array<double, 3>{0, 45, 50}), Status::ok);
  EXPECT_EQ(t.writes(), writes + 1);
  EXPECT_EQ(text(t.last_write()), "#0P1500#7P1250#31P1500S4000T20\r");
  EXPECT_EQ(link.last_send_size(), t.last_write().size());
  for (int tick = 1; tick <= 50; ++tick) {
    const double s = tick / 50.0;
    ASSERT_EQ(link.send(std::array<double, 3>{90 * s, -90 * s, 50 + 50 * s}), Status::ok);
    board.advance(0.01);
    EXPECT_TRUE(board.output_pulse(0) > 1500 + 1000 * s / 2 - 12);  // halfway through the sweep
    board.advance(0.01);
    EXPECT_NEAR(board.output_pulse(0), 1500 + 500 * s, 1e-6);  // and there at the tick's end
  }
  std::array<double, 3> positions{};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_TRUE(known[0] && known[1] && known[2]);
  EXPECT_NEAR(positions[0], 90, 0.9);  // 10 µs resolution
  EXPECT_NEAR(positions[1], -90, 0.9);
  EXPECT_NEAR(positions[2], 100, 0.9);
}

TEST(Ssc32Link, ReleasedChannelsAreHeldLowOnce) {
  SimSsc32 board({});
  SimWire t(board);
  fw::Ssc32Link link(t, ssc32_link_config());
  const std::array<double, 3> frame{0, 0, 50};
  ASSERT_EQ(link.send(frame), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(text(t.last_write()), "#7L\r#0P1500#31P1500S4000T20\r");
  EXPECT_EQ(board.output_pulse(7), 0);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(text(t.last_write()), "#0P1500#31P1500S4000T20\r");
  std::array<double, 3> positions{};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_FALSE(known[1]);  // no pulse: unknown
  ASSERT_EQ(link.release(), Status::ok);
  EXPECT_EQ(text(t.last_write()), "#0L#7L#31L\r");
  EXPECT_EQ(board.output_pulse(0), 0);
}

class SilentDevice final : public ByteDevice {
 public:
  void receive(std::span<const std::uint8_t> bytes) override { received += bytes.size(); }
  std::size_t take_replies(std::span<std::uint8_t>) override { return 0; }
  void advance(double) override {}
  std::uint64_t bytes_received() const override { return received; }
  std::uint64_t received = 0;
};

TEST(Ssc32Link, ASilentBoardIsATimeoutAndBadSetupIsRefused) {
  SilentDevice silent;
  SimWire t(silent);
  fw::Ssc32Link link(t, ssc32_link_config());
  EXPECT_EQ(link.start(), Status::timeout);
  fw::Ssc32LinkConfig twice = ssc32_link_config();
  twice.actuators[1].device_channel = 0;
  EXPECT_THROW(fw::Ssc32Link(t, twice), std::invalid_argument);
  fw::Ssc32LinkConfig outside = ssc32_link_config();
  outside.actuators[1].device_channel = 32;
  EXPECT_THROW(fw::Ssc32Link(t, outside), std::invalid_argument);
}

TEST(Ssc32Link, EndToEndThroughTheSerialTransportAndAPseudoTerminal) {
  SimSsc32 board({});
  PtyDeviceHost host(board, PtyDeviceHost::Clock::stepped);
  fw::SerialTransport port(host.slave_path(), 115200);
  fw::Ssc32LinkConfig config = ssc32_link_config();
  config.reply_timeout = 2000ms;
  fw::Ssc32Link link(port, config);
  ASSERT_EQ(link.start(), Status::ok);
  for (int tick = 1; tick <= 40; ++tick) {
    const double s = std::min(1.0, tick / 25.0);
    ASSERT_EQ(link.send(std::array<double, 3>{45 * s, 30 * s, 20}), Status::ok);
    ASSERT_TRUE(host.wait_consumed(port.bytes_written(), 2000ms));
    host.with_device([](ByteDevice& d) { d.advance(0.02); });
  }
  std::array<double, 3> positions{};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_NEAR(positions[0], 45, 0.9);
  EXPECT_NEAR(positions[1], 30, 0.9);
  EXPECT_NEAR(positions[2], 20, 0.9);
  EXPECT_NEAR(host.with_device([](ByteDevice& d) { return static_cast<SimSsc32&>(d).servo_position_us(0); }), 1750, 3);
}

}  // namespace
}  // namespace avar::sim
