// The simulated Feetech bus answers as the notes describe, byte for byte where they give bytes.
#include "avar/sim/sim_feetech.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "../support/encode.hpp"

namespace avar::sim {
namespace {

namespace ft = firmware_iface::feetech;
using Bytes = std::vector<std::uint8_t>;

SimFeetechConfig bus(ft::Series series = ft::Series::sts) {
  SimFeetechConfig c;
  c.series = series;
  SimFeetechServo a;
  a.id = 1;
  a.initial_position = series == ft::Series::sts ? 2048 : 512;
  SimFeetechServo b = a;
  b.id = 2;
  b.initial_position = series == ft::Series::sts ? 1024 : 300;
  c.servos = {a, b};
  c.log_limit = 50;
  return c;
}

Bytes replies(SimFeetech& d) {
  std::array<std::uint8_t, 512> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

TEST(SimFeetech, F1_PingIsAnsweredWithAnEmptyStatus) {
  SimFeetech d(bus());
  d.receive(Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB});
  EXPECT_EQ(replies(d), (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x00, 0xFC}));
  d.receive(Bytes{0xFF, 0xFF, 0x09, 0x02, 0x01, 0xF3});  // nobody has ID 9
  EXPECT_TRUE(replies(d).empty());
}

TEST(SimFeetech, F2_F3_ReadPresentPositionLittleEndianOnSts) {
  SimFeetech d(bus());
  d.receive(Bytes{0xFF, 0xFF, 0x01, 0x04, 0x02, 0x38, 0x02, 0xBE});
  EXPECT_EQ(replies(d), (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x00, 0x00, 0x08, 0xF2}));
}

TEST(SimFeetech, ScsKeepsWordsBigEndian) {
  SimFeetech d(bus(ft::Series::scs));
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_read(o, 1, ft::kPresentPosition, 2); }));
  const Bytes r = replies(d);
  ASSERT_EQ(r.size(), 8u);
  EXPECT_EQ(r[5], 0x02);  // 512 high byte first
  EXPECT_EQ(r[6], 0x00);
  EXPECT_EQ(d.read_word(0, 3), 1284);  // SCS0009
  // F5: SCS write of goal 512 is accepted and answered.
  d.receive(Bytes{0xFF, 0xFF, 0x01, 0x05, 0x03, 0x2A, 0x02, 0x00, 0xCA});
  EXPECT_EQ(replies(d), (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x00, 0xFC}));
  EXPECT_EQ(d.read_word(0, ft::kGoalPosition), 512);
}

TEST(SimFeetech, F7_SyncWriteIsSilentAndMovesTheServosOnceTorqueIsOn) {
  SimFeetech d(bus());
  const Bytes on{1};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, ft::kBroadcastId, ft::kTorqueEnable, on); }));
  EXPECT_TRUE(replies(d).empty());  // broadcasts are never answered
  // F7 asks ID 1 for 2048 (where it is) and ID 2 for 1024 (where it is): swap them instead.
  const std::uint8_t ids[2] = {1, 2};
  const std::uint16_t goals[2] = {1024, 2048};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_sync_write_words(o, ft::Series::sts, ft::kGoalPosition, ids, goals); }));
  EXPECT_TRUE(replies(d).empty());
  d.advance(0.1);
  EXPECT_LT(d.position(0), 2048 - 100);
  EXPECT_GT(d.position(1), 1024 + 100);
  EXPECT_EQ(d.read_u8(0, ft::kMoving), 1);
  d.advance(2.0);
  EXPECT_NEAR(d.position(0), 1024, 1.5);
  EXPECT_NEAR(d.position(1), 2048, 1.5);
  EXPECT_EQ(d.read_u8(0, ft::kMoving), 0);
}

TEST(SimFeetech, F8_SyncReadRepliesInListedOrder) {
  SimFeetech d(bus());
  d.receive(Bytes{0xFF, 0xFF, 0xFE, 0x06, 0x82, 0x38, 0x02, 0x02, 0x01, 0x3C});  // IDs 2, 1 (same sum)
  const Bytes r = replies(d);
  ft::Packet p;
  std::size_t used = 0;
  ASSERT_EQ(ft::decode_packet(r, &p, &used), ft::DecodeResult::ok);
  EXPECT_EQ(p.id, 2);
  EXPECT_EQ(ft::get_word(ft::Series::sts, p.params), 1024);
  ASSERT_EQ(ft::decode_packet(std::span(r).subspan(used), &p, &used), ft::DecodeResult::ok);
  EXPECT_EQ(p.id, 1);
  EXPECT_EQ(ft::get_word(ft::Series::sts, p.params), 2048);
}

TEST(SimFeetech, SpeedAndAccelerationLimitTheMove) {
  SimFeetech d(bus());
  std::array<std::uint8_t, 7> block{10};  // 1000 steps/s², goal 3048, time 0, speed 500 steps/s
  ft::put_word(ft::Series::sts, std::span<std::uint8_t, 2>(&block[1], 2), 3048);
  ft::put_word(ft::Series::sts, std::span<std::uint8_t, 2>(&block[5], 2), 500);
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 1, ft::kAcceleration, block); }));
  const Bytes on{1};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 1, ft::kTorqueEnable, on); }));
  replies(d);
  d.advance(0.2);  // accelerating: at most 1000/2 * 0.2² = 20 steps
  EXPECT_LE(d.position(0) - 2048, 20.5);
  EXPECT_GT(d.position(0) - 2048, 5);
  d.advance(1.0);  // then no faster than 500 steps/s
  EXPECT_LE(d.position(0) - 2048, 20.5 + 500 * 1.0 + 1);
  const int speed = ft::from_sign_magnitude(d.read_word(0, ft::kPresentSpeed), ft::kSpeedSignBit);
  EXPECT_LE(speed, 500);
  EXPECT_GT(speed, 400);
}

TEST(SimFeetech, ErrorRepliesForBadChecksumUnknownInstructionAndOutOfRangeWrites) {
  SimFeetech d(bus());
  d.receive(Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFA});  // ping with a wrong checksum
  EXPECT_EQ(replies(d), testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_packet(o, 1, ft::kErrorChecksum, {}); }));
  EXPECT_EQ(d.checksum_errors(), 1u);
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_packet(o, 1, 0x30, {}); }));  // no such instruction
  EXPECT_EQ(replies(d), testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_packet(o, 1, ft::kErrorInstruction, {}); }));
  const Bytes range_reply = testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_packet(o, 1, ft::kErrorRange, {}); });
  // Goal outside the position limits: refused, nothing written.
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_write_word(o, ft::Series::sts, 1, ft::kGoalPosition, 5000); }));
  EXPECT_EQ(replies(d), range_reply);
  EXPECT_EQ(d.read_word(0, ft::kGoalPosition), 2048);
  // Read-only register, torque value that does not exist, past the end of the table.
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_write_word(o, ft::Series::sts, 1, ft::kPresentPosition, 1); }));
  EXPECT_EQ(replies(d), range_reply);
  const Bytes three{3};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 1, ft::kTorqueEnable, three); }));
  EXPECT_EQ(replies(d), range_reply);
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_read(o, 1, 70, 4); }));
  EXPECT_EQ(replies(d), range_reply);
  // None of that reaches anyone on a broadcast.
  d.receive(Bytes{0xFF, 0xFF, 0xFE, 0x02, 0x01, 0x00});
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_write_word(o, ft::Series::sts, ft::kBroadcastId, ft::kGoalPosition, 5000); }));
  EXPECT_TRUE(replies(d).empty());
}

TEST(SimFeetech, ResponseLevelZeroAnswersOnlyReadAndPing) {
  SimFeetech d(bus());
  const Bytes zero{0};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 1, ft::kResponseLevel, zero); }));
  EXPECT_EQ(replies(d).size(), 6u);  // the level in force when the write arrived
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_write_word(o, ft::Series::sts, 1, ft::kGoalPosition, 2000); }));
  EXPECT_TRUE(replies(d).empty());
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_ping(o, 1); }));
  EXPECT_EQ(replies(d).size(), 6u);
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_read(o, 1, ft::kGoalPosition, 2); }));
  EXPECT_EQ(replies(d).size(), 8u);
}

TEST(SimFeetech, RegWriteWaitsForAction) {
  SimFeetech d(bus());
  std::array<std::uint8_t, 2> word{};
  ft::put_word(ft::Series::sts, word, 1500);
  Bytes params{ft::kGoalPosition, word[0], word[1]};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_packet(o, 1, ft::kRegWrite, params); }));
  EXPECT_EQ(replies(d).size(), 6u);
  EXPECT_EQ(d.read_word(0, ft::kGoalPosition), 2048);
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_packet(o, ft::kBroadcastId, ft::kAction, {}); }));
  EXPECT_TRUE(replies(d).empty());
  EXPECT_EQ(d.read_word(0, ft::kGoalPosition), 1500);
}

TEST(SimFeetech, TemperatureRisesWithLoadUntilTheOverheatProtectionCutsTorque) {
  SimFeetechConfig c = bus();
  c.servos[0].heating_c_per_s_at_full_load = 10;
  SimFeetech d(c);
  const Bytes on{1};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, ft::kBroadcastId, ft::kTorqueEnable, on); }));
  d.set_external_load(0, 0.8);
  d.advance(1.0);
  EXPECT_GT(d.temperature_c(0), 31);
  EXPECT_NEAR(d.temperature_c(1), 25, 0.01);  // no load, no heat
  EXPECT_NEAR(ft::from_sign_magnitude(d.read_word(0, ft::kPresentLoad), ft::kLoadSignBit), 800, 5);
  for (int i = 0; i < 200 && d.read_u8(0, ft::kTorqueEnable) == 1; ++i) d.advance(0.1);
  EXPECT_NEAR(d.temperature_c(0), 70, 1);  // cut at the limit
  EXPECT_EQ(d.read_u8(0, ft::kStatus) & ft::kErrorOverheat, ft::kErrorOverheat);
  EXPECT_EQ(d.read_u8(0, ft::kTorqueEnable), 0);
  // Every reply now carries the overheat bit.
  d.receive(testing::encode_into<ft::kMaxPacketSize>([](auto o) { return ft::encode_ping(o, 1); }));
  const Bytes r = replies(d);
  ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(r[4], ft::kErrorOverheat);
}

TEST(SimFeetech, ModelsItsLineRateAndReturnDelay) {
  SimFeetech d(bus());
  EXPECT_DOUBLE_EQ(d.wire_time(56), 56 * 10 / 1e6);
  EXPECT_EQ(d.read_u8(0, ft::kBaudRate), 0);
  EXPECT_DOUBLE_EQ(d.reply_delay_s(0), 0);
  const Bytes delay{250};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 1, ft::kReturnDelay, delay); }));
  EXPECT_DOUBLE_EQ(d.reply_delay_s(0), 500e-6);
  EXPECT_EQ(SimFeetech::baud_code(115200), 4);
  EXPECT_EQ(SimFeetech::baud_code(123), -1);
  SimFeetechConfig bad = bus();
  bad.baud = 123;
  EXPECT_THROW(SimFeetech{bad}, std::invalid_argument);
  bad = bus();
  bad.servos[1].id = 1;
  EXPECT_THROW(SimFeetech{bad}, std::invalid_argument);
}

TEST(SimFeetech, RecentreMakesThePresentPositionTheCentre) {
  SimFeetechConfig c = bus();
  SimFeetech d(c);
  const Bytes centre{128};
  d.receive(testing::encode_into<ft::kMaxPacketSize>([&](auto o) { return ft::encode_write(o, 2, ft::kTorqueEnable, centre); }));
  EXPECT_EQ(replies(d).size(), 6u);
  EXPECT_EQ(d.read_word(1, ft::kPresentPosition), 2048);
  EXPECT_EQ(d.read_u8(1, ft::kTorqueEnable), 0);
}

}  // namespace
}  // namespace avar::sim
