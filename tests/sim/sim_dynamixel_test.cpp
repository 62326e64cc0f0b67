// The simulated DYNAMIXEL bus answers exactly as X-series servos do, byte for byte where the
// protocol notes give the bytes.
#include "avar/sim/sim_dynamixel.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "../support/encode.hpp"

namespace avar::sim {
namespace {

namespace dxl = firmware_iface::dynamixel;
using Bytes = std::vector<std::uint8_t>;

SimDynamixelConfig dynamixel_bus() {
  SimDynamixelConfig c;
  SimDynamixelServo a;
  a.id = 1;
  a.model_number = 1030;  // XM430-W210, as in the notes' ping example
  a.firmware = 38;
  a.initial_position = 166;
  SimDynamixelServo b = a;
  b.id = 2;
  b.initial_position = 2079;
  c.servos = {a, b};
  c.log_limit = 100;
  return c;
}

Bytes replies(SimDynamixel& d) {
  std::array<std::uint8_t, 512> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

TEST(SimDynamixel, D1_D2_PingAnswersWithModelAndFirmware) {
  SimDynamixel d(dynamixel_bus());
  d.receive(Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E});
  EXPECT_EQ(replies(d), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D}));
}

TEST(SimDynamixel, D4_D5_ReadPresentPosition) {
  SimDynamixel d(dynamixel_bus());
  d.receive(Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15});
  EXPECT_EQ(replies(d), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55, 0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0}));
}

TEST(SimDynamixel, D11_SyncReadRepliesInListedOrder) {
  SimDynamixel d(dynamixel_bus());
  d.receive(Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x09, 0x00, 0x82, 0x84, 0x00, 0x04, 0x00, 0x01, 0x02, 0xCE, 0xFA});
  const Bytes r = replies(d);
  std::array<std::uint8_t, 64> scratch{};
  dxl::Status s;
  std::size_t used = 0;
  ASSERT_EQ(dxl::decode_status(r, scratch, &s, &used), dxl::DecodeResult::ok);
  EXPECT_EQ(s.id, 1);
  EXPECT_EQ(dxl::read_i32(s.params), 166);
  ASSERT_EQ(dxl::decode_status(std::span(r).subspan(used), scratch, &s, &used), dxl::DecodeResult::ok);
  EXPECT_EQ(s.id, 2);
  EXPECT_EQ(dxl::read_i32(s.params), 2079);
  // The notes give the end of ID 2's reply: ... 55 00 1F 08 00 00 BA BE.
  EXPECT_EQ(Bytes(r.end() - 8, r.end()), (Bytes{0x55, 0x00, 0x1F, 0x08, 0x00, 0x00, 0xBA, 0xBE}));
}

TEST(SimDynamixel, D12_SyncWriteThenTheServosMove) {
  SimDynamixel d(dynamixel_bus());
  const Bytes torque{0x01};
  d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, dxl::kBroadcastId, dxl::kTorqueEnable, torque); }));
  EXPECT_TRUE(replies(d).empty());  // broadcast writes are not answered
  d.receive(Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x11, 0x00, 0x83, 0x74, 0x00, 0x04, 0x00, 0x01, 0x96, 0x00, 0x00, 0x00, 0x02,
                  0xAA, 0x00, 0x00, 0x00, 0x82, 0x87});
  EXPECT_EQ(d.read_i32(0, dxl::kGoalPosition), 150);
  EXPECT_EQ(d.read_i32(1, dxl::kGoalPosition), 170);
  for (int i = 0; i < 200; ++i) d.advance(0.005);
  EXPECT_NEAR(d.position(0), 150, 1);
  EXPECT_NEAR(d.position(1), 170, 1);
  EXPECT_TRUE(replies(d).empty());
}

TEST(SimDynamixel, WritesAreCheckedAsTheServoChecksThem) {
  SimDynamixel d(dynamixel_bus());
  std::array<std::uint8_t, 64> scratch{};
  dxl::Status s;
  std::size_t used = 0;
  const auto error_of = [&](const Bytes& request) {
    d.receive(request);
    const Bytes r = replies(d);
    EXPECT_EQ(dxl::decode_status(r, scratch, &s, &used), dxl::DecodeResult::ok);
    return s.processing_error();
  };
  const Bytes model{0x00, 0x00};
  EXPECT_EQ(error_of(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kModelNumber, model); })), 0x07);  // read-only
  const Bytes far{0x00, 0x20, 0x00, 0x00};  // 8192 > max position limit 4095
  EXPECT_EQ(error_of(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kGoalPosition, far); })), 0x06);
  const Bytes on{0x01};
  EXPECT_EQ(error_of(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kTorqueEnable, on); })), 0x00);
  const Bytes delay{0x00};
  EXPECT_EQ(error_of(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kReturnDelayTime, delay); })), 0x07);  // EEPROM, torque on
  EXPECT_EQ(error_of(testing::encode_into<256>([](auto o) { return dxl::encode_instruction(o, 1, 0x77, {}); })), 0x02);  // unknown instruction
  Bytes bad_crc = testing::encode_into<256>([](auto o) { return dxl::encode_ping(o, 2); });
  bad_crc.back() ^= 0xFF;
  EXPECT_EQ(error_of(bad_crc), 0x03);
  EXPECT_EQ(d.crc_errors(), 1u);
}

TEST(SimDynamixel, StatusReturnLevelDecidesWhoAnswers) {
  SimDynamixel d(dynamixel_bus());
  const Bytes zero{0x00};
  d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kStatusReturnLevel, zero); }));
  EXPECT_FALSE(replies(d).empty());  // the write itself is answered at the old level
  d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kLed, Bytes{0x01}); }));
  EXPECT_TRUE(replies(d).empty());
  d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_read(o, 1, dxl::kPresentPosition, 4); }));
  EXPECT_TRUE(replies(d).empty());
  d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_ping(o, 1); }));
  EXPECT_FALSE(replies(d).empty());  // Ping always answers
}

TEST(SimDynamixel, HeavyWorkOverheatsShutsDownAndRaisesTheAlertUntilReboot) {
  SimDynamixelConfig c = dynamixel_bus();
  c.servos[0].heating_c_per_s_at_full_load = 400;  // a servo stalled in a hot box
  SimDynamixel d(c);
  d.receive(testing::encode_into<256>([](auto o) { return dxl::encode_write(o, 1, dxl::kTorqueEnable, Bytes{0x01}); }));
  replies(d);
  std::int32_t goal = 0;
  for (int i = 0; i < 2000 && d.read_u8(0, dxl::kHardwareErrorStatus) == 0; ++i) {
    goal = goal == 0 ? 4000 : 0;  // slam back and forth
    const Bytes g{static_cast<std::uint8_t>(goal & 0xFF), static_cast<std::uint8_t>(goal >> 8), 0, 0};
    d.receive(testing::encode_into<256>([&](auto o) { return dxl::encode_write(o, 1, dxl::kGoalPosition, g); }));
    replies(d);
    for (int k = 0; k < 5; ++k) d.advance(0.01);
  }
  EXPECT_EQ(d.read_u8(0, dxl::kHardwareErrorStatus), 0x04);
  EXPECT_EQ(d.read_u8(0, dxl::kTorqueEnable), 0);
  EXPECT_GT(d.temperature_c(0), 80);
  std::array<std::uint8_t, 64> scratch{};
  dxl::Status s;
  std::size_t used = 0;
  d.receive(testing::encode_into<256>([](auto o) { return dxl::encode_ping(o, 1); }));
  ASSERT_EQ(dxl::decode_status(replies(d), scratch, &s, &used), dxl::DecodeResult::ok);
  EXPECT_TRUE(s.alert());
  EXPECT_EQ(dxl::describe_hardware_error(d.read_u8(0, dxl::kHardwareErrorStatus)), "overheating");
  // Torque cannot come back until a reboot.
  d.receive(testing::encode_into<256>([](auto o) { return dxl::encode_write(o, 1, dxl::kTorqueEnable, Bytes{0x01}); }));
  ASSERT_EQ(dxl::decode_status(replies(d), scratch, &s, &used), dxl::DecodeResult::ok);
  EXPECT_EQ(s.processing_error(), 0x07);
  d.receive(testing::encode_into<256>([](auto o) { return dxl::encode_reboot(o, 1); }));
  replies(d);
  EXPECT_EQ(d.read_u8(0, dxl::kHardwareErrorStatus), 0);
}

TEST(SimDynamixel, SurvivesNoiseAndSplitPackets) {
  SimDynamixel d(dynamixel_bus());
  const Bytes ping = testing::encode_into<256>([](auto o) { return dxl::encode_ping(o, 2); });
  d.receive(Bytes{0x00, 0xFF, 0x13});
  d.receive(std::span(ping).first(5));
  EXPECT_TRUE(replies(d).empty());
  d.receive(std::span(ping).subspan(5));
  EXPECT_FALSE(replies(d).empty());
  EXPECT_EQ(d.log().back().id, 2);
}

}  // namespace
}  // namespace avar::sim
