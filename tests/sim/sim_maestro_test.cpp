// The simulated Maestro decodes exactly the bytes the device accepts and answers with the exact
// reply bytes (../shared/protocols/pololu-maestro.md).
#include "avar/sim/sim_maestro.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::sim {
namespace {

namespace maestro = firmware_iface::maestro;
using Bytes = std::vector<std::uint8_t>;

SimMaestroConfig config(bool crc = false) {
  SimMaestroConfig c;
  c.crc = crc;
  c.log_limit = 100;
  return c;
}

Bytes replies(SimMaestro& d) {
  std::array<std::uint8_t, 64> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

TEST(SimMaestro, CompactSetTargetThenGetPosition) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});  // M1: ch 0 = 6000
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0x90, 0x00});
  EXPECT_EQ(replies(d), (Bytes{0x70, 0x17}));  // M12
  ASSERT_EQ(d.log().size(), 2u);
  EXPECT_EQ(d.log()[0].command, 0x84);
  EXPECT_EQ(d.log()[0].values, (std::vector<std::uint16_t>{6000}));
}

TEST(SimMaestro, PololuFormForThisDeviceActsAndForAnotherIsIgnored) {
  SimMaestro d(config());
  d.receive(Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E});  // M3, device 12
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0xAA, 0x05, 0x04, 0x01, 0x70, 0x2E});  // device 5: not us
  EXPECT_EQ(d.target(1), 0);
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestro, SetMultipleTargetsAndTargetZeroStopsPulses) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x03, 0x70, 0x2E});
  d.receive(Bytes{0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E});  // M5: ch 3 off, ch 4 = 6000
  EXPECT_EQ(d.target(3), 0);
  EXPECT_EQ(d.output_pulse(3), 0);
  EXPECT_EQ(d.target(4), 6000);
}

TEST(SimMaestro, MiniSscNeutralAndEnds) {
  SimMaestro d(config());
  d.receive(Bytes{0xFF, 0x00, 0x7F});  // M4: neutral
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0xFF, 0x01, 0xFE});  // 254 = neutral + 476.25 µs
  EXPECT_EQ(d.target(1), 7905);
}

TEST(SimMaestro, TargetsAreClampedToTheChannelRange) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F});  // 1000 µs: inside 992..2000
  EXPECT_EQ(d.target(0), 4000);
  d.receive(Bytes{0x84, 0x00, 0x7F, 0x7F});  // 4095.75 µs: clamped to 2000 µs
  EXPECT_EQ(d.target(0), 8000);
}

TEST(SimMaestro, CrcIsCheckedAndABadOneIsAnError) {
  SimMaestro d(config(true));
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E, 0x2B});  // M8
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0x84, 0x01, 0x70, 0x2E, 0x2B});  // wrong CRC for channel 1
  EXPECT_EQ(d.target(1), 0);
  EXPECT_EQ(d.errors(), maestro::kSerialCrcError);
  d.receive(Bytes{0xAA, 0x01, 0x10, 0x00, 0x6B});  // M7 is for device 1: ignored, CRC not checked
  EXPECT_TRUE(replies(d).empty());
}

TEST(SimMaestro, GetErrorsRepliesAndClears) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00});        // interrupted by the next command byte
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});
  d.receive(Bytes{0xC5});              // unknown command
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
  d.receive(Bytes{0xA1});
  EXPECT_EQ(replies(d), (Bytes{0x10, 0x00}));
  EXPECT_EQ(d.errors(), 0);
  d.receive(Bytes{0xA1});
  EXPECT_EQ(replies(d), (Bytes{0x00, 0x00}));
}

TEST(SimMaestro, AnErrorSendsEveryChannelHome) {
  SimMaestroConfig c = config();
  c.channels[0].home_us = 1500;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x84, 0x01, 0x20, 0x1F});
  d.receive(Bytes{0xC5});
  EXPECT_EQ(d.target(0), 6000);  // its home position
  EXPECT_EQ(d.target(1), 0);     // home "off": pulses stop
}

TEST(SimMaestro, MicroMaestroHasNoSetMultipleTargets) {
  SimMaestroConfig c = config();
  c.channel_count = 6;
  SimMaestro d(c);
  d.receive(Bytes{0x9F, 0x01, 0x00, 0x70, 0x2E});
  EXPECT_EQ(d.target(0), 0);
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
}

TEST(SimMaestro, SpeedLimitMatchesTheGuidesWorkedExample) {
  // Speed 140 = 3.5 µs/ms: 1000 -> 1350 µs takes 100 ms.
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x05, 0x20, 0x1F});  // 1000 µs (first pulse: immediate)
  d.receive(Bytes{0x87, 0x05, 0x0C, 0x01});  // M6: speed 140
  EXPECT_EQ(d.speed(5), 140);
  std::array<std::uint8_t, 4> packet{};
  const auto n = maestro::encode_set_target(packet, {}, 5, 5400);
  d.receive(std::span(packet.data(), n));
  for (int i = 0; i < 99; ++i) d.advance(0.001);
  EXPECT_LT(d.output_pulse(5), 5400);
  EXPECT_NEAR(d.output_pulse(5), 4000 + 14 * 99, 1e-6);
  d.advance(0.001);
  EXPECT_DOUBLE_EQ(d.output_pulse(5), 5400);
}

TEST(SimMaestro, AccelerationRampsSpeedUpAndDown) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F});  // 1000 µs
  d.receive(Bytes{0x89, 0x00, 0x04, 0x00});  // acceleration 4 = 1250 µs/s²
  d.receive(Bytes{0x84, 0x00, 0x40, 0x3E});  // to 2000 µs
  // Without a speed limit a 1000 µs move at 1250 µs/s² takes 2*sqrt(1000/1250) = 1.79 s.
  double t = 0;
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x01});  // moving
  while (d.output_pulse(0) != 8000 && t < 5) {
    d.advance(0.001);
    t += 0.001;
  }
  EXPECT_NEAR(t, 1.79, 0.03);
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x00});
}

TEST(SimMaestro, ServoFollowsTheOutputWithLag) {
  SimMaestroConfig c = config();
  c.channels[0].initial_position_us = 1500;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x40, 0x3E});  // 2000 µs
  d.advance(0.01);
  EXPECT_GT(d.servo_position_us(0), 1500);
  EXPECT_LT(d.servo_position_us(0), 2000);
  for (int i = 0; i < 100; ++i) d.advance(0.01);
  EXPECT_NEAR(d.servo_position_us(0), 2000, 2.0);
}

TEST(SimMaestro, BaudDetectionByteIsConsumed) {
  SimMaestroConfig c = config();
  c.baud_detect = true;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});  // before detection: noise at an unknown rate
  EXPECT_EQ(d.target(0), 0);
  d.receive(Bytes{0xAA, 0x84, 0x00, 0x70, 0x2E});
  EXPECT_EQ(d.target(0), 6000);
  EXPECT_EQ(d.errors(), 0);
}

}  // namespace
}  // namespace avar::sim
