// Golden bytes from ../shared/protocols/ssc32.md, section 6 (vectors S1..S4), the manual's
// examples through the line parser, and encode/parse round trips.
#include "avar/firmware_iface/ssc32_codec.hpp"

#include <gtest/gtest.h>

#include "../support/encode.hpp"

#include <random>
#include <string>
#include <vector>

namespace avar::firmware_iface::ssc32 {
namespace {

using avar::testing::Bytes;

template <class F>
Bytes encode(F&& f) {
  return avar::testing::encode_into<kMaxLineSize>(f);
}

ParseResult parse(const std::string& text, Command* c) {
  return parse_line(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), c);
}

TEST(Ssc32Codec, S1_S2_SingleServoMovesWithSpeedOrTime) {
  const ServoMove s1[] = {{5, 1500, 750}};
  EXPECT_EQ(encode([&](auto o) { return encode_group_move(o, s1, 0); }),
            (Bytes{0x23, 0x35, 0x50, 0x31, 0x35, 0x30, 0x30, 0x53, 0x37, 0x35, 0x30, 0x0D}));
  const ServoMove s2[] = {{3, 1600, 0}};
  EXPECT_EQ(encode([&](auto o) { return encode_group_move(o, s2, 1000); }),
            (Bytes{0x23, 0x33, 0x50, 0x31, 0x36, 0x30, 0x30, 0x54, 0x31, 0x30, 0x30, 0x30, 0x0D}));
}

TEST(Ssc32Codec, S3_S4_Queries) {
  EXPECT_EQ(encode([](auto o) { return encode_query_movement(o); }), (Bytes{0x51, 0x0D}));
  const std::uint8_t five[] = {5};
  EXPECT_EQ(encode([&](auto o) { return encode_query_pulse(o, five); }), (Bytes{0x51, 0x50, 0x35, 0x0D}));
  EXPECT_EQ(reply_from_pulse(1500), 0x96);
  EXPECT_EQ(pulse_from_reply(0x96), 1500);
  EXPECT_EQ(reply_from_pulse(0), 0);
  const std::uint8_t several[] = {0, 17};
  const Bytes two = encode([&](auto o) { return encode_query_pulse(o, several); });
  EXPECT_EQ(std::string(two.begin(), two.end()), "QP0QP17\r");
}

TEST(Ssc32Codec, SixteenServoGroupIs119Bytes) {
  std::vector<ServoMove> moves;
  for (std::uint8_t ch = 0; ch < 16; ++ch) moves.push_back({ch, 1500, 0});
  EXPECT_EQ(encode([&](auto o) { return encode_group_move(o, moves, 0); }).size(), 119u);  // the notes' wire cost
  const Bytes with_time = encode([&](auto o) { return encode_group_move(o, moves, 20); });
  EXPECT_EQ(std::string(with_time.end() - 4, with_time.end()), "T20\r");
}

TEST(Ssc32Codec, EncodersSaturateAndRefuse) {
  const ServoMove wide[] = {{0, 100, 0}, {1, 9000, 0}};
  EXPECT_EQ(encode([&](auto o) { return encode_group_move(o, wide, 70000); }),
            (Bytes{'#', '0', 'P', '5', '0', '0', '#', '1', 'P', '2', '5', '0', '0', 'T', '6', '5', '5', '3', '5', '\r'}));
  const ServoMove bad[] = {{32, 1500, 0}};
  EXPECT_TRUE(encode([&](auto o) { return encode_group_move(o, bad, 0); }).empty());
  std::array<std::uint8_t, 4> tiny{};
  const ServoMove ok[] = {{1, 1500, 0}};
  EXPECT_EQ(encode_group_move(tiny, ok, 0), 0u);
  const std::uint8_t low[] = {3, 4};
  const Bytes off = encode([&](auto o) { return encode_outputs_low(o, low); });
  EXPECT_EQ(std::string(off.begin(), off.end()), "#3L#4L\r");
}

TEST(Ssc32Codec, ParsesTheManualsExamples) {
  Command c;
  ASSERT_EQ(parse("#5 P1600 #10 P750 T2500 ", &c), ParseResult::ok);
  EXPECT_EQ(c.kind, Command::Kind::move);
  ASSERT_EQ(c.servo_count, 2u);
  EXPECT_EQ(c.servos[0].channel, 5);
  EXPECT_EQ(c.servos[0].pulse_us, 1600);
  EXPECT_EQ(c.servos[1].channel, 10);
  EXPECT_EQ(c.servos[1].pulse_us, 750);
  EXPECT_EQ(c.time_ms, 2500u);
  ASSERT_EQ(parse("#5 P1600 #17 P750 S500 #2 P2250 T2000 ", &c), ParseResult::ok);
  EXPECT_EQ(c.servos[1].speed_us_per_s, 500);
  EXPECT_EQ(c.servos[2].pulse_us, 2250);
  ASSERT_EQ(parse("#5p1500s750", &c), ParseResult::ok);  // lower case
  EXPECT_EQ(c.servos[0].speed_us_per_s, 750);
  ASSERT_EQ(parse("#5 PO -20 #6 PO 15", &c), ParseResult::ok);
  EXPECT_EQ(c.kind, Command::Kind::offset);
  EXPECT_EQ(c.offsets[0], -20);
  ASSERT_EQ(parse("QP 5 QP 6", &c), ParseResult::ok);
  EXPECT_EQ(c.kind, Command::Kind::query_pulse);
  ASSERT_EQ(c.query_count, 2u);
  EXPECT_EQ(c.query[1], 6);
  ASSERT_EQ(parse("QP 5 6", &c), ParseResult::ok);
  EXPECT_EQ(c.query_count, 2u);
  ASSERT_EQ(parse("q", &c), ParseResult::ok);
  EXPECT_EQ(c.kind, Command::Kind::query_movement);
  ASSERT_EQ(parse("#3H #4l", &c), ParseResult::ok);
  EXPECT_EQ(c.kind, Command::Kind::output);
  EXPECT_EQ(c.servos[0].pulse_us, 1);
  EXPECT_EQ(c.servos[1].pulse_us, 0);
  EXPECT_EQ(parse("  \t", &c), ParseResult::empty);
}

TEST(Ssc32Codec, RejectsWhatTheBoardIgnores) {
  Command c;
  EXPECT_EQ(parse("#5P1500 #6PO10", &c), ParseResult::invalid);  // kinds mixed
  EXPECT_EQ(parse("#32P1500", &c), ParseResult::invalid);
  EXPECT_EQ(parse("#5P3000", &c), ParseResult::invalid);
  EXPECT_EQ(parse("#5P1500T100#6P1500", &c), ParseResult::invalid);  // T ends the group
  EXPECT_EQ(parse("#5PO200", &c), ParseResult::invalid);
  EXPECT_EQ(parse("T100", &c), ParseResult::invalid);
  EXPECT_EQ(parse("#5X", &c), ParseResult::invalid);
  EXPECT_EQ(parse("hello", &c), ParseResult::invalid);
  EXPECT_EQ(parse("#5P15000000", &c), ParseResult::invalid);
}

TEST(Ssc32Codec, RandomGroupsRoundTripThroughTheParser) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<ServoMove> moves(std::uniform_int_distribution<std::size_t>(1, 32)(rng));
    for (ServoMove& m : moves) {
      m.channel = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 31)(rng));
      m.pulse_us = static_cast<std::uint16_t>(std::uniform_int_distribution<int>(500, 2500)(rng));
      m.speed_us_per_s = static_cast<std::uint16_t>(std::uniform_int_distribution<int>(0, 1)(rng) * std::uniform_int_distribution<int>(1, 65535)(rng));
    }
    const std::uint32_t time = std::uniform_int_distribution<std::uint32_t>(0, 65535)(rng);
    const Bytes line = encode([&](auto o) { return encode_group_move(o, moves, time); });
    ASSERT_FALSE(line.empty());
    ASSERT_EQ(line.back(), kCr);
    Command c;
    ASSERT_EQ(parse_line(std::span(line).first(line.size() - 1), &c), ParseResult::ok);
    ASSERT_EQ(c.servo_count, moves.size());
    EXPECT_EQ(c.time_ms, time);
    for (std::size_t i = 0; i < moves.size(); ++i) {
      EXPECT_EQ(c.servos[i].channel, moves[i].channel);
      EXPECT_EQ(c.servos[i].pulse_us, moves[i].pulse_us);
      EXPECT_EQ(c.servos[i].speed_us_per_s, moves[i].speed_us_per_s);
    }
  }
}

}  // namespace
}  // namespace avar::firmware_iface::ssc32
