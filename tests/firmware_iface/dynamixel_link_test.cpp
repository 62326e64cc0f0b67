// The DYNAMIXEL driver against the simulated bus: the bytes it puts on the wire, the telemetry
// it brings back, and its handling of every wire fault (lost, corrupt, duplicated and late
// replies, a silent servo, an unplugged port that comes back), in memory on a simulated clock
// and end to end through the real serial transport on a pseudo-terminal.
#include "avar/firmware_iface/dynamixel_link.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/faulty_device.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_wire.hpp"
#include "../support/temp_file.hpp"

namespace avar::firmware_iface {
namespace {

namespace dxl = dynamixel;
constexpr int kBaud = 1'000'000;

sim::SimDynamixelConfig bus(int servos) {
  sim::SimDynamixelConfig c;
  for (int i = 0; i < servos; ++i) {
    sim::SimDynamixelServo s;
    s.id = static_cast<std::uint8_t>(i + 1);
    c.servos.push_back(s);
  }
  return c;
}

/// Channel i in degrees, -90..90, on servo ID i+1 (1024..3072 pulses).
DynamixelLinkConfig link_config(int servos, DynamixelReadback readback) {
  DynamixelLinkConfig c;
  c.readback = readback;
  for (int i = 0; i < servos; ++i) {
    DynamixelActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.id = static_cast<std::uint8_t>(i + 1);
    a.calibration = {-90, 90, 1024, 3072, false, 0};
    c.actuators.push_back(a);
  }
  return c;
}

struct Bench {
  explicit Bench(int servos, DynamixelReadback readback = DynamixelReadback::full, sim::FaultPlan plan = {})
      : device(bus(servos)), faulty(device, plan), wire(faulty, kBaud), link(wire, link_config(servos, readback)),
        frame(static_cast<std::size_t>(servos), 0.0), telemetry(static_cast<std::size_t>(servos)) {}
  sim::SimDynamixel device;
  sim::FaultyDevice faulty;
  sim::SimWire wire;
  DynamixelLink link;
  std::vector<double> frame;
  std::vector<ChannelTelemetry> telemetry;
  std::vector<double> last_fresh;  ///< per channel: the position of its last reply

  /// One send; then every channel's telemetry is either fresh (counted, kept in last_fresh) or
  /// absent (unknown position, load and temperature), never the old value of an earlier reply.
  Status send_and_check_telemetry() {
    std::vector<std::uint64_t> updates(telemetry.size());
    for (std::size_t c = 0; c < telemetry.size(); ++c) updates[c] = telemetry[c].updates;
    const Status s = link.send(frame);
    link.read_telemetry(telemetry);
    last_fresh.resize(telemetry.size(), ChannelTelemetry::kUnknown);
    for (std::size_t c = 0; c < telemetry.size(); ++c) {
      const ChannelTelemetry& t = telemetry[c];
      if (t.updates > updates[c]) {
        EXPECT_TRUE(std::isfinite(t.position)) << "channel " << c;
        last_fresh[c] = t.position;
      } else {
        EXPECT_TRUE(std::isnan(t.position) && std::isnan(t.load) && std::isnan(t.temperature_c)) << "channel " << c;
      }
    }
    return s;
  }
};

TEST(DynamixelLink, StartEnablesTorqueAndEachSendIsOneSyncWrite) {
  Bench b(4, DynamixelReadback::none);
  ASSERT_EQ(b.link.start(), Status::ok) << b.link.start_problem();
  for (std::size_t s = 0; s < 4; ++s) EXPECT_EQ(b.device.read_u8(s, dxl::kTorqueEnable), 1);
  b.frame = {-90, 0, 45, 90};
  ASSERT_EQ(b.link.send(b.frame), Status::ok);
  // Sync Write of 4 goal positions: 14 + 5 * 4 bytes, and nothing else.
  EXPECT_EQ(b.link.last_exchange_bytes(), 34u);
  EXPECT_EQ(b.device.read_i32(0, dxl::kGoalPosition), 1024);
  EXPECT_EQ(b.device.read_i32(1, dxl::kGoalPosition), 2048);
  EXPECT_EQ(b.device.read_i32(2, dxl::kGoalPosition), 2560);
  EXPECT_EQ(b.device.read_i32(3, dxl::kGoalPosition), 3072);
}

TEST(DynamixelLink, WriteOnlyBytesPerTickMatchTheProtocolMinimum) {
  for (int n : {1, 16, 32}) {
    Bench b(n, DynamixelReadback::none);
    ASSERT_EQ(b.link.start(), Status::ok);
    ASSERT_EQ(b.link.send(b.frame), Status::ok);
    EXPECT_EQ(b.link.last_exchange_bytes(), static_cast<std::size_t>(14 + 5 * n)) << n << " servos";
  }
}

TEST(DynamixelLink, SaturatesOutsideTheCalibrationAndCountsIt) {
  Bench b(1, DynamixelReadback::none);
  ASSERT_EQ(b.link.start(), Status::ok);
  b.frame = {500};
  ASSERT_EQ(b.link.send(b.frame), Status::ok);
  EXPECT_EQ(b.device.read_i32(0, dxl::kGoalPosition), 3072);
  EXPECT_EQ(b.link.saturated_pulses(), 1u);
}

TEST(DynamixelLink, TelemetryFollowsTheServosMotion) {
  Bench b(3);
  ASSERT_EQ(b.link.start(), Status::ok);
  b.frame = {30, -30, 60};
  for (int tick = 0; tick < 400; ++tick) ASSERT_EQ(b.link.send(b.frame), Status::ok);
  b.link.read_telemetry(b.telemetry);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(b.telemetry[c].position, b.frame[c], 0.2) << "channel " << c;
    EXPECT_TRUE(std::isfinite(b.telemetry[c].load));
    EXPECT_NEAR(b.telemetry[c].temperature_c, 25, 3);
    EXPECT_EQ(b.telemetry[c].faults, 0u);
    EXPECT_EQ(b.telemetry[c].updates, 400u);
  }
  const LinkCounters k = b.link.counters();
  EXPECT_EQ(k.exchanges, 400u);
  EXPECT_EQ(k.replies, 400u * 3 + 3 * 6);  // start: ping, 2 reads, 2 profile writes, torque on
  EXPECT_EQ(k.crc_errors + k.timeouts + k.framing_errors, 0u);
}

TEST(DynamixelLink, ReadPositionsMapsPulsesBackToChannelUnits) {
  sim::SimDynamixelConfig c = bus(2);
  c.servos[0].initial_position = 1024;
  c.servos[1].initial_position = 2560;
  sim::SimDynamixel device(c);
  sim::SimWire wire(device, kBaud);
  DynamixelLink link(wire, link_config(2, DynamixelReadback::position));
  std::vector<double> frame(2, 0.0);
  std::array<bool, 2> known{};
  ASSERT_EQ(link.read_positions(frame, known), Status::ok);
  EXPECT_TRUE(known[0] && known[1]);
  EXPECT_DOUBLE_EQ(frame[0], -90);
  EXPECT_DOUBLE_EQ(frame[1], 45);
}

TEST(DynamixelLink, RejectsDuplicateAndOutOfRangeIds) {
  sim::SimDynamixel device(bus(1));
  sim::SimWire wire(device, kBaud);
  DynamixelLinkConfig c = link_config(2, DynamixelReadback::none);
  c.actuators[1].id = 1;
  EXPECT_THROW(DynamixelLink(wire, c), std::invalid_argument);
  c.actuators[1].id = 253;
  EXPECT_THROW(DynamixelLink(wire, c), std::invalid_argument);
}

TEST(DynamixelLink, StartNamesAServoThatDoesNotAnswer) {
  sim::SimDynamixel device(bus(1));
  sim::SimWire wire(device, kBaud);
  DynamixelLink link(wire, link_config(2, DynamixelReadback::full));
  EXPECT_EQ(link.start(), Status::timeout);
  EXPECT_NE(link.start_problem().find("servo ID 2 does not answer a ping"), std::string::npos) << link.start_problem();
}

TEST(DynamixelLink, ReadbackNeedsAStatusReturnLevelThatAnswersReads) {
  sim::SimDynamixel device(bus(1));
  std::array<std::uint8_t, 32> packet{};
  const std::array<std::uint8_t, 1> level0{0};
  device.receive(std::span(packet.data(), dxl::encode_write(packet, 1, dxl::kStatusReturnLevel, level0)));
  sim::SimWire wire(device, kBaud);
  DynamixelLink link(wire, link_config(1, DynamixelReadback::full));
  EXPECT_NE(link.start(), Status::ok);
  EXPECT_NE(link.start_problem().find("Status Return Level"), std::string::npos) << link.start_problem();
}

TEST(DynamixelLink, CorruptRepliesAreCountedAndSyncIsKept) {
  sim::FaultPlan plan;
  plan.corrupt_reply = 0.3;
  plan.seed = 7;
  Bench b(4, DynamixelReadback::full);
  ASSERT_EQ(b.link.start(), Status::ok);
  b.faulty.set_plan(plan);
  b.frame = {10, 20, 30, 40};
  for (int tick = 0; tick < 500; ++tick) ASSERT_EQ(b.send_and_check_telemetry(), Status::ok) << "tick " << tick;
  const LinkCounters k = b.link.counters();
  EXPECT_GT(b.faulty.counts().replies_corrupted, 50u);
  EXPECT_GT(k.crc_errors + k.framing_errors, 0u);
  EXPECT_GT(k.retries, 0u);
  for (std::size_t c = 0; c < 4; ++c) {
    EXPECT_NEAR(b.last_fresh[c], b.frame[c], 0.2);
    EXPECT_GT(b.telemetry[c].updates, 300u);  // most ticks still bring fresh telemetry
  }
}

TEST(DynamixelLink, LostDuplicatedAndLateRepliesNeverStallOrDesynchronise) {
  for (const char* fault : {"drop", "duplicate", "late"}) {
    sim::FaultPlan plan;
    plan.seed = 3;
    if (std::string(fault) == "drop") plan.drop_reply = 0.2;
    if (std::string(fault) == "duplicate") plan.duplicate_reply = 0.5;
    if (std::string(fault) == "late") plan.delay_reply_s = 0.002;  // well inside the reply timeout
    Bench b(4, DynamixelReadback::full);
    ASSERT_EQ(b.link.start(), Status::ok);
    b.faulty.set_plan(plan);
    b.frame = {-10, -20, 10, 20};
    const double before = b.wire.now_s();
    for (int tick = 0; tick < 300; ++tick) ASSERT_EQ(b.send_and_check_telemetry(), Status::ok) << fault << " tick " << tick;
    // Bounded: no exchange ever waits longer than one reply timeout plus retries.
    EXPECT_LT((b.wire.now_s() - before) / 300, 0.025) << fault;
    for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(b.last_fresh[c], b.frame[c], 0.2) << fault;
  }
}

TEST(DynamixelLink, ASilentServoBecomesAWatchdogTimeoutAfterItsExchanges) {
  Bench b(2);
  ASSERT_EQ(b.link.start(), Status::ok);
  sim::FaultPlan silent;
  silent.silent = true;
  b.faulty.set_plan(silent);
  int ticks = 0;
  Status s = Status::ok;
  while (s == Status::ok && ticks < 100) {
    s = b.link.send(b.frame);
    ++ticks;
  }
  EXPECT_EQ(s, Status::timeout);
  EXPECT_EQ(ticks, 10);  // silent_exchanges
  EXPECT_GE(b.link.counters().timeouts, 10u);
}

TEST(DynamixelLink, AnUnpluggedPortFailsThenReconnectsAndReenablesTorque) {
  Bench b(2, DynamixelReadback::position);
  ASSERT_EQ(b.link.start(), Status::ok);
  ASSERT_EQ(b.link.send(b.frame), Status::ok);
  b.wire.set_connected(false);
  EXPECT_EQ(b.link.send(b.frame), Status::io_error);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(b.link.send(b.frame), Status::io_error);
  EXPECT_EQ(b.link.counters().reconnects, 0u);
  // The servos lost power with the adapter.
  std::array<std::uint8_t, 32> packet{};
  const std::array<std::uint8_t, 1> off{0};
  b.device.receive(std::span(packet.data(), dxl::encode_write(packet, dxl::kBroadcastId, dxl::kTorqueEnable, off)));
  b.wire.set_connected(true);
  Status s = Status::io_error;
  for (int i = 0; i < 20 && s != Status::ok; ++i) s = b.link.send(b.frame);
  EXPECT_EQ(s, Status::ok);
  EXPECT_EQ(b.link.counters().reconnects, 1u);
  EXPECT_EQ(b.device.read_u8(0, dxl::kTorqueEnable), 1);
  EXPECT_EQ(b.device.read_u8(1, dxl::kTorqueEnable), 1);
}

TEST(DynamixelLink, AnOverheatedServoReportsItsHardwareErrorAsADeviceFault) {
  sim::SimDynamixelConfig c = bus(2);
  c.servos[1].ambient_c = 79;
  c.servos[1].heating_c_per_s_at_full_load = 2000;
  sim::SimDynamixel device(c);
  sim::SimWire wire(device, kBaud);
  DynamixelLink link(wire, link_config(2, DynamixelReadback::full));
  ASSERT_EQ(link.start(), Status::ok);
  std::vector<double> frame{0, 0};
  std::vector<ChannelTelemetry> telemetry(2);
  for (int tick = 0; tick < 200; ++tick) {
    frame[1] = tick % 2 ? 90 : -90;  // keep it working hard
    (void)link.send(frame);
  }
  link.read_telemetry(telemetry);
  EXPECT_EQ(telemetry[0].faults, 0u);
  EXPECT_TRUE(telemetry[1].faults & kDeviceOverheat) << "faults " << telemetry[1].faults;
  EXPECT_GE(telemetry[1].temperature_c, 80);
}

TEST(DynamixelLink, ReleaseTurnsTorqueOffOnEveryServo) {
  Bench b(3, DynamixelReadback::none);
  ASSERT_EQ(b.link.start(), Status::ok);
  b.link.release_channel(1);
  ASSERT_EQ(b.link.send(b.frame), Status::ok);
  EXPECT_EQ(b.device.read_u8(1, dxl::kTorqueEnable), 0);
  EXPECT_EQ(b.device.read_u8(0, dxl::kTorqueEnable), 1);
  ASSERT_EQ(b.link.release(), Status::ok);
  for (std::size_t s = 0; s < 3; ++s) EXPECT_EQ(b.device.read_u8(s, dxl::kTorqueEnable), 0);
}

TEST(DynamixelLink, EndToEndThroughTheSerialPortOnAPseudoTerminal) {
  sim::SimDynamixel device(bus(3));
  sim::PtyDeviceHost host(device, sim::PtyDeviceHost::Clock::wall);
  SerialTransport port(host.slave_path(), kBaud);
  DynamixelLinkConfig config = link_config(3, DynamixelReadback::full);
  config.reply_timeout = std::chrono::milliseconds(200);
  DynamixelLink link(port, config);
  ASSERT_EQ(link.start(), Status::ok) << link.start_problem();
  std::vector<double> frame{15, -15, 45};
  std::vector<ChannelTelemetry> telemetry(3);
  for (int tick = 0; tick < 30; ++tick) ASSERT_EQ(link.send(frame), Status::ok);
  host.with_device([](sim::ByteDevice& d) {
    auto& dx = static_cast<sim::SimDynamixel&>(d);
    EXPECT_EQ(dx.read_i32(0, dxl::kGoalPosition), 2219);
    EXPECT_EQ(dx.read_i32(2, dxl::kGoalPosition), 2560);
    return 0;
  });
  link.read_telemetry(telemetry);
  for (const ChannelTelemetry& t : telemetry) {
    EXPECT_EQ(t.updates, 30u);
    EXPECT_TRUE(std::isfinite(t.position));
  }
  EXPECT_EQ(link.counters().crc_errors + link.counters().timeouts, 0u);
}

TEST(DynamixelLink, ReconnectsWhenThePortComesBackUnderTheSamePath) {
  // A udev-style symlink stands for /dev/serial/by-id/...: the adapter is unplugged (the pty
  // closes) and plugged back in (a new pty, the symlink follows it).
  const std::string path = avar::testing::temp_path("port");
  sim::SimDynamixel device(bus(1));
  auto host = std::make_unique<sim::PtyDeviceHost>(device, sim::PtyDeviceHost::Clock::wall);
  std::filesystem::create_symlink(host->slave_path(), path);
  SerialTransport port(path, kBaud);
  DynamixelLinkConfig config = link_config(1, DynamixelReadback::position);
  config.reply_timeout = std::chrono::milliseconds(200);
  config.reconnect_every = 1;
  DynamixelLink link(port, config);
  ASSERT_EQ(link.start(), Status::ok);
  std::vector<double> frame{0};
  ASSERT_EQ(link.send(frame), Status::ok);
  host.reset();
  EXPECT_NE(link.send(frame), Status::ok);
  EXPECT_EQ(link.send(frame), Status::io_error);  // still gone: reopen fails
  host = std::make_unique<sim::PtyDeviceHost>(device, sim::PtyDeviceHost::Clock::wall);
  std::filesystem::remove(path);
  std::filesystem::create_symlink(host->slave_path(), path);
  Status s = Status::io_error;
  for (int i = 0; i < 5 && s != Status::ok; ++i) s = link.send(frame);
  EXPECT_EQ(s, Status::ok);
  EXPECT_EQ(link.counters().reconnects, 1u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace avar::firmware_iface
