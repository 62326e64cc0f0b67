// FeetechLink against the simulated bus: in memory (deterministic, every counter checked) and
// end to end through the real SerialTransport and a pseudo-terminal.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "avar/firmware_iface/feetech_link.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/faulty_device.hpp"
#include "avar/sim/sim_wire.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_feetech.hpp"

namespace avar::sim {
namespace {

namespace fw = firmware_iface;
namespace ft = firmware_iface::feetech;
using namespace std::chrono_literals;

SimFeetechConfig three_servos(ft::Series series = ft::Series::sts) {
  SimFeetechConfig c;
  c.series = series;
  for (int id : {3, 5, 9}) {
    SimFeetechServo s;
    s.id = static_cast<std::uint8_t>(id);
    c.servos.push_back(s);
  }
  return c;
}

/// Channels in degrees, ±90° over 1024..3072 steps (STS) or 256..768 (SCS); rig channels 0..2
/// are IDs 3, 5, 9.
fw::FeetechLinkConfig link_config(ft::Series series = ft::Series::sts, std::vector<std::uint8_t> ids = {3, 5, 9}) {
  fw::FeetechLinkConfig c;
  c.series = series;
  const double half = ft::position_resolution(series) / 4.0;
  const double centre = ft::position_resolution(series) / 2.0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    c.actuators.push_back({i, ids[i], {-90, 90, centre - half, centre + half, i == 1, 0}, {}, {}});
  return c;
}

/// A device between the driver and the bus that spoils replies on request.
class SpoilingDevice final : public ByteDevice {
 public:
  explicit SpoilingDevice(ByteDevice& d) : inner_(d) {}
  void receive(std::span<const std::uint8_t> bytes) override { inner_.receive(bytes); }
  std::size_t take_replies(std::span<std::uint8_t> out) override {
    if (noise_before && out.size() > 1) {  // a glitch byte on the line just before a reply
      const std::size_t n = inner_.take_replies(out.subspan(1));
      if (n == 0) return 0;
      out[0] = 0x5A;
      noise_before = false;
      return 1 + n;
    }
    const std::size_t n = inner_.take_replies(out);
    if (flip_at >= 0 && static_cast<std::size_t>(flip_at) < n) out[static_cast<std::size_t>(flip_at)] ^= 0x01;
    if (flip_at >= 0) flip_at -= static_cast<int>(n);  // counts reply bytes across reads
    return n;
  }
  void advance(double dt) override { inner_.advance(dt); }
  std::uint64_t bytes_received() const override { return inner_.bytes_received(); }
  int flip_at = -1;  ///< reply bytes to let through before flipping one
  bool noise_before = false;

 private:
  ByteDevice& inner_;
};

TEST(FeetechLink, StartPingsHoldsPositionAndTurnsTorqueOn) {
  SimFeetech bus(three_servos());
  SimWire t(bus);
  fw::FeetechLink link(t, link_config());
  ASSERT_EQ(link.start(), Status::ok);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(bus.read_u8(i, ft::kTorqueEnable), 1);
    EXPECT_EQ(bus.read_word(i, ft::kGoalPosition), 2048);
  }
  EXPECT_EQ(link.counters().timeouts, 0u);
  EXPECT_NE(link.describe().find("Feetech STS bus (IDs 3,5,9"), std::string::npos) << link.describe();
}

TEST(FeetechLink, StartFailsOnASilentServo) {
  SimFeetech bus(three_servos());
  SimWire t(bus);
  fw::FeetechLink link(t, link_config(ft::Series::sts, {3, 5, 7}));
  EXPECT_EQ(link.start(), Status::timeout);
  EXPECT_EQ(link.counters().timeouts, 1u);
}

TEST(FeetechLink, EachTickIsOneWriteOfSyncWriteAndSyncReadAndFillsTelemetry) {
  SimFeetech bus(three_servos());
  SimWire t(bus);
  fw::FeetechLink link(t, link_config());
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 3> frame{45, 45, -30};  // channel 1 is reversed
  std::array<fw::ChannelTelemetry, 3> telemetry{};
  for (int tick = 0; tick < 100; ++tick) {
    const std::uint64_t writes = t.writes();
    ASSERT_EQ(link.send(frame), Status::ok);
    EXPECT_EQ(t.writes(), writes + 1);
    bus.advance(0.01);
  }
  EXPECT_EQ(link.last_send_size(), ft::sync_write_size(2, 3) + ft::sync_read_size(3));
  EXPECT_EQ(link.reply_bytes_per_tick(), 3 * ft::status_size(8));
  // The packet on the wire: goals 2560, 1536 (reversed), 1707, then the sync read of 8 bytes.
  ft::Packet p;
  std::size_t used = 0;
  ASSERT_EQ(ft::decode_packet(t.last_write(), &p, &used), ft::DecodeResult::ok);
  EXPECT_EQ(p.code, ft::kSyncWrite);
  EXPECT_EQ(ft::get_word(ft::Series::sts, p.params.subspan(3, 2)), 2560);
  EXPECT_EQ(ft::get_word(ft::Series::sts, p.params.subspan(6, 2)), 1536);
  EXPECT_EQ(ft::get_word(ft::Series::sts, p.params.subspan(9, 2)), 1707);
  ASSERT_EQ(ft::decode_packet(std::span(t.last_write()).subspan(used), &p, &used), ft::DecodeResult::ok);
  EXPECT_EQ(p.code, ft::kSyncRead);
  EXPECT_NEAR(bus.position(0), 2560, 1.5);
  EXPECT_NEAR(bus.position(1), 1536, 1.5);
  ASSERT_EQ(link.send(frame), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_NEAR(telemetry[0].position, 45, 0.1);
  EXPECT_NEAR(telemetry[1].position, 45, 0.1);
  EXPECT_NEAR(telemetry[2].position, -30, 0.1);
  EXPECT_NEAR(telemetry[0].temperature_c, 25, 1);
  EXPECT_TRUE(std::isfinite(telemetry[0].load));
  EXPECT_EQ(telemetry[0].faults, 0u);
  EXPECT_EQ(telemetry[0].updates, 101u);
  const fw::LinkCounters c = link.counters();
  EXPECT_EQ(c.crc_errors + c.framing_errors + c.timeouts + c.device_errors, 0u);
  // start(): ping, speed, acceleration, present position, goal, torque per servo; then 101 ticks.
  EXPECT_EQ(c.replies, 3u * 6 + 3 * 101);
}

TEST(FeetechLink, ScsSeriesSpeaksBigEndian) {
  SimFeetech bus(three_servos(ft::Series::scs));
  SimWire t(bus);
  fw::FeetechLinkConfig config = link_config(ft::Series::scs);
  config.readback = fw::FeetechReadback::position;
  fw::FeetechLink link(t, config);
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 3> frame{90, 0, -90};
  for (int tick = 0; tick < 100; ++tick) {
    ASSERT_EQ(link.send(frame), Status::ok);
    bus.advance(0.01);
  }
  EXPECT_EQ(bus.read_word(0, ft::kGoalPosition), 768);
  EXPECT_EQ(bus.read_word(2, ft::kGoalPosition), 256);
  EXPECT_NEAR(bus.position(0), 768, 1.5);
  std::array<double, 3> positions{};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_TRUE(known[0] && known[1] && known[2]);
  EXPECT_NEAR(positions[0], 90, 0.5);
  EXPECT_NEAR(positions[2], -90, 0.5);
}

TEST(FeetechLink, OverheatAndLoadReachTelemetryAsDeviceFaults) {
  SimFeetechConfig sc = three_servos();
  sc.servos[2].heating_c_per_s_at_full_load = 20;
  SimFeetech bus(sc);
  SimWire t(bus);
  fw::FeetechLink link(t, link_config());
  ASSERT_EQ(link.start(), Status::ok);
  bus.set_external_load(2, -0.9);
  const std::array<double, 3> frame{0, 0, 0};
  std::array<fw::ChannelTelemetry, 3> telemetry{};
  ASSERT_EQ(link.send(frame), Status::ok);
  bus.advance(0.01);
  ASSERT_EQ(link.send(frame), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_NEAR(telemetry[2].load, -0.9, 0.01);
  for (int tick = 0; tick < 1000 && !(telemetry[2].faults & fw::kDeviceOverheat); ++tick) {
    bus.advance(0.01);
    ASSERT_EQ(link.send(frame), Status::ok);
    link.read_telemetry(telemetry);
  }
  EXPECT_EQ(telemetry[2].faults, fw::kDeviceOverheat);
  EXPECT_GT(telemetry[2].temperature_c, 69);
  EXPECT_EQ(telemetry[0].faults, 0u);
  EXPECT_GT(link.counters().device_errors, 0u);
}

TEST(FeetechLink, CorruptRepliesAreCountedAndTheNextTickIsInSync) {
  SimFeetech bus(three_servos());
  SpoilingDevice spoil(bus);
  SimWire t(spoil);
  fw::FeetechLinkConfig config = link_config();
  config.readback = fw::FeetechReadback::position;
  fw::FeetechLink link(t, config);
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 3> frame{10, 20, 30};
  std::array<fw::ChannelTelemetry, 3> telemetry{};
  spoil.flip_at = 8 + 6;  // a data byte of the second reply
  config.retries = 0;
  fw::FeetechLink no_retry(t, config);
  EXPECT_EQ(no_retry.send(frame), Status::ok);  // counted, recovered from: no fault for one lost reply
  no_retry.read_telemetry(telemetry);
  EXPECT_TRUE(std::isfinite(telemetry[0].position));
  EXPECT_TRUE(std::isnan(telemetry[1].position));  // absent, not old
  EXPECT_TRUE(std::isfinite(telemetry[2].position));
  EXPECT_EQ(no_retry.counters().crc_errors, 1u);
  EXPECT_EQ(no_retry.counters().timeouts, 1u);
  // With a retry (the default), the lost reply is read again in the same send.
  spoil.flip_at = 8 + 6;
  EXPECT_EQ(link.send(frame), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_TRUE(std::isfinite(telemetry[1].position));
  EXPECT_EQ(link.counters().crc_errors, 1u);
  EXPECT_EQ(link.counters().retries, 1u);
  spoil.noise_before = true;
  EXPECT_EQ(link.send(frame), Status::ok);  // a stray byte skipped, every reply taken
  EXPECT_EQ(link.counters().framing_errors, 1u);
  EXPECT_EQ(link.send(frame), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_TRUE(std::isfinite(telemetry[1].position));
}

TEST(FeetechLink, ASilentServoBecomesAWatchdogTimeoutAndAnUnpluggedPortReconnects) {
  SimFeetech bus(three_servos());
  sim::FaultyDevice faulty(bus, {});
  SimWire t(faulty);
  fw::FeetechLinkConfig config = link_config();
  config.readback = fw::FeetechReadback::position;
  config.reply_timeout = std::chrono::milliseconds(2);
  fw::FeetechLink link(t, config);
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 3> frame{10, 20, 30};
  sim::FaultPlan silent;
  silent.silent = true;
  faulty.set_plan(silent);
  int sends = 0;
  Status s = Status::ok;
  while (s == Status::ok && sends < 100) {
    s = link.send(frame);
    ++sends;
  }
  EXPECT_EQ(s, Status::timeout);
  EXPECT_EQ(sends, 10);  // silent_exchanges
  faulty.set_plan({});
  EXPECT_EQ(link.send(frame), Status::ok);  // answers again: no longer silent
  t.set_connected(false);
  EXPECT_EQ(link.send(frame), Status::io_error);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(link.send(frame), Status::io_error);
  t.set_connected(true);
  Status back = Status::io_error;
  for (int i = 0; i < 20 && back != Status::ok; ++i) back = link.send(frame);
  EXPECT_EQ(back, Status::ok);
  EXPECT_EQ(link.counters().reconnects, 1u);
}

TEST(FeetechLink, LostDuplicatedAndLateRepliesAreRecoveredFrom) {
  for (const char* fault : {"drop", "corrupt", "duplicate", "late"}) {
    SimFeetech bus(three_servos());
    sim::FaultyDevice faulty(bus, {});
    SimWire t(faulty);
    fw::FeetechLink link(t, link_config());
    ASSERT_EQ(link.start(), Status::ok) << fault;
    sim::FaultPlan plan;
    plan.seed = 11;
    if (std::string(fault) == "drop") plan.drop_reply = 0.2;
    if (std::string(fault) == "corrupt") plan.corrupt_reply = 0.2;
    if (std::string(fault) == "duplicate") plan.duplicate_reply = 0.5;
    if (std::string(fault) == "late") plan.delay_reply_s = 0.001;
    faulty.set_plan(plan);
    const std::array<double, 3> frame{10, 20, 30};
    std::array<fw::ChannelTelemetry, 3> telemetry{};
    for (int tick = 0; tick < 300; ++tick) {
      ASSERT_EQ(link.send(frame), Status::ok) << fault << " tick " << tick;
      bus.advance(0.01);
    }
    link.read_telemetry(telemetry);
    EXPECT_GT(telemetry[0].updates, 200u) << fault;
  }
}

TEST(FeetechLink, ReleasedChannelsGoLimpAndLeaveTheSyncWrite) {
  SimFeetech bus(three_servos());
  SimWire t(bus);
  fw::FeetechLinkConfig config = link_config();
  config.readback = fw::FeetechReadback::none;
  fw::FeetechLink link(t, config);
  ASSERT_EQ(link.start(), Status::ok);
  const std::array<double, 3> frame{10, 20, 30};
  link.release_channel(1);
  link.release_channel(7);  // not this link's: ignored
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(bus.read_u8(1, ft::kTorqueEnable), 0);
  EXPECT_EQ(bus.read_u8(0, ft::kTorqueEnable), 1);
  EXPECT_EQ(link.last_send_size(), ft::sync_write_size(2, 2) + ft::sync_write_size(1, 1));
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(link.last_send_size(), ft::sync_write_size(2, 2));  // torque-off sent once
  ASSERT_EQ(link.release(), Status::ok);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(bus.read_u8(i, ft::kTorqueEnable), 0);
}

TEST(FeetechLink, RejectsBadConfigurations) {
  SimFeetech bus(three_servos());
  SimWire t(bus);
  EXPECT_THROW(fw::FeetechLink(t, link_config(ft::Series::sts, {3, 3})), std::invalid_argument);
  EXPECT_THROW(fw::FeetechLink(t, link_config(ft::Series::sts, {254})), std::invalid_argument);
  EXPECT_THROW(fw::FeetechLink(t, fw::FeetechLinkConfig{}), std::invalid_argument);
}

TEST(FeetechLink, EndToEndThroughTheSerialTransportAndAPseudoTerminal) {
  SimFeetech bus(three_servos());
  PtyDeviceHost host(bus, PtyDeviceHost::Clock::stepped);
  fw::SerialTransport port(host.slave_path(), 1000000);
  fw::FeetechLinkConfig config = link_config();
  config.reply_timeout = 500ms;  // generous: a loaded test machine, not a real bus
  fw::FeetechLink link(port, config);
  ASSERT_EQ(link.start(), Status::ok);
  std::array<fw::ChannelTelemetry, 3> telemetry{};
  for (int tick = 0; tick < 50; ++tick) {
    const double s = tick / 50.0;
    const std::array<double, 3> frame{60 * s, -60 * s, 30 * s};
    ASSERT_EQ(link.send(frame), Status::ok);
    ASSERT_TRUE(host.wait_consumed(port.bytes_written(), 2000ms));
    host.with_device([](ByteDevice& d) { d.advance(0.02); });
  }
  for (int tick = 0; tick < 30; ++tick) {
    ASSERT_EQ(link.send(std::array<double, 3>{60, -60, 30}), Status::ok);
    ASSERT_TRUE(host.wait_consumed(port.bytes_written(), 2000ms));
    host.with_device([](ByteDevice& d) { d.advance(0.02); });
  }
  ASSERT_EQ(link.send(std::array<double, 3>{60, -60, 30}), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_NEAR(telemetry[0].position, 60, 0.2);
  EXPECT_NEAR(telemetry[1].position, -60, 0.2);
  EXPECT_NEAR(telemetry[2].position, 30, 0.2);
  EXPECT_EQ(link.counters().timeouts, 0u);
  EXPECT_EQ(link.counters().crc_errors, 0u);
  std::array<double, 3> positions{};
  std::array<bool, 3> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_NEAR(positions[1], -60, 0.2);
  ASSERT_EQ(link.release(), Status::ok);
  ASSERT_TRUE(host.wait_consumed(port.bytes_written(), 2000ms));
  EXPECT_EQ(host.with_device([](ByteDevice& d) { return static_cast<SimFeetech&>(d).read_u8(0, ft::kTorqueEnable); }), 0);
}

}  // namespace
}  // namespace avar::sim
