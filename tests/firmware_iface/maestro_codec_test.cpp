// Golden bytes from ../shared/protocols/pololu-maestro.md, section 7 (vectors M1..M12).
#include "avar/firmware_iface/maestro_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace avar::firmware_iface::maestro {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <class F>
Bytes encode(F&& f) {
  std::array<std::uint8_t, kMaxPacketSize> buf{};
  const std::size_t n = f(std::span<std::uint8_t>(buf));
  return Bytes(buf.begin(), buf.begin() + static_cast<long>(n));
}

const Framing kCompact{};
const Framing kPololu12{true, 12, false};

TEST(MaestroCodec, M1_M2_CompactSetTarget) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 6000); }), (Bytes{0x84, 0x00, 0x70, 0x2E}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 2, 6000); }), (Bytes{0x84, 0x02, 0x70, 0x2E}));
}

TEST(MaestroCodec, M3_PololuSetTarget) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kPololu12, 0, 6000); }), (Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E}));
}

TEST(MaestroCodec, M4_MiniSsc) {
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 0, 127); }), (Bytes{0xFF, 0x00, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 0, 255); }), Bytes{});
}

TEST(MaestroCodec, M5_SetMultipleTargets) {
  const std::array<std::uint16_t, 2> targets{0, 6000};
  EXPECT_EQ(encode([&](auto o) { return encode_set_multiple_targets(o, kCompact, 3, targets); }),
            (Bytes{0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E}));
}

TEST(MaestroCodec, M6_SetSpeed) {
  EXPECT_EQ(encode([](auto o) { return encode_set_speed(o, kCompact, 5, 140); }), (Bytes{0x87, 0x05, 0x0C, 0x01}));
}

TEST(MaestroCodec, M7_GetPositionPololuWithCrc) {
  EXPECT_EQ(encode([](auto o) { return encode_get_position(o, Framing{true, 1, true}, 0); }), (Bytes{0xAA, 0x01, 0x10, 0x00, 0x6B}));
}

TEST(MaestroCodec, M8_M9_M10_Crc7) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, Framing{false, 12, true}, 0, 6000); }),
            (Bytes{0x84, 0x00, 0x70, 0x2E, 0x2B}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, Framing{true, 12, true}, 0, 6000); }),
            (Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E, 0x22}));
  const std::array<std::uint8_t, 2> m10{0x83, 0x01};
  EXPECT_EQ(crc7(m10), 0x17);
}

TEST(MaestroCodec, M11_PulseEnds) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 4000); }), (Bytes{0x84, 0x00, 0x20, 0x1F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 8000); }), (Bytes{0x84, 0x00, 0x40, 0x3E}));
}

TEST(MaestroCodec, M12_PositionReply) {
  const std::array<std::uint8_t, 2> reply{0x70, 0x17};
  EXPECT_EQ(decode_position_reply(reply), 6000);
}

TEST(MaestroCodec, QueriesAndReplies) {
  EXPECT_EQ(encode([](auto o) { return encode_get_errors(o, kCompact); }), Bytes{0xA1});
  EXPECT_EQ(encode([](auto o) { return encode_get_moving_state(o, kCompact); }), Bytes{0x93});
  EXPECT_EQ(encode([](auto o) { return encode_go_home(o, kPololu12); }), (Bytes{0xAA, 0x0C, 0x22}));
  EXPECT_EQ(encode([](auto o) { return encode_set_acceleration(o, kCompact, 1, 4); }), (Bytes{0x89, 0x01, 0x04, 0x00}));
  const std::array<std::uint8_t, 2> errors{0x10, 0x01};
  EXPECT_EQ(decode_errors_reply(errors), kSerialProtocolError | kScriptProgramCounterError);
  EXPECT_EQ(describe_errors(0x0018), "serial CRC error, serial protocol error");
  EXPECT_EQ(describe_errors(0), "none");
  const std::array<std::uint8_t, 1> moving{0x01};
  EXPECT_TRUE(decode_moving_state_reply(moving));
}

TEST(MaestroCodec, ValuesSaturateNeverWrap) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 0xFFFF); }), (Bytes{0x84, 0x00, 0x7F, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_acceleration(o, kCompact, 0, 1000); }), (Bytes{0x89, 0x00, 0x7F, 0x01}));
  EXPECT_EQ(quarter_us_from_us(1e9), kMaxValue);
  EXPECT_EQ(quarter_us_from_us(-5), 0);
  EXPECT_EQ(quarter_us_from_us(1500.1), 6000);
}

TEST(MaestroCodec, InvalidArgumentsAndSmallBuffersWriteNothing) {
  std::array<std::uint8_t, 3> small{};
  EXPECT_EQ(encode_set_target(small, kCompact, 0, 6000), 0u);
  std::array<std::uint8_t, kMaxPacketSize> buf{};
  EXPECT_EQ(encode_set_target(buf, kCompact, 24, 6000), 0u);
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 0, {}), 0u);
  const std::array<std::uint16_t, 3> three{6000, 6000, 6000};
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 22, three), 0u);
  EXPECT_EQ(encode_get_errors(buf, Framing{true, 128, false}), 0u);
  const std::array<std::uint16_t, 24> all{};
  EXPECT_EQ(encode_set_multiple_targets(buf, Framing{true, 12, true}, 0, all), kMaxPacketSize);
}

TEST(MaestroCodec, UnitConversionsFromTheGuide) {
  // Speed 140 = 3.5 µs/ms; speed 4 = 100 µs/s; acceleration 4 = 1250 µs/s².
  EXPECT_DOUBLE_EQ(us_per_s_from_speed_units(140), 3500.0);
  EXPECT_EQ(speed_units_from_us_per_s(3500.0), 140);
  EXPECT_EQ(speed_units_from_us_per_s(100.0), 4);
  EXPECT_EQ(speed_units_from_us_per_s(1.0), 1);  // slowest, never "unlimited"
  EXPECT_EQ(acceleration_units_from_us_per_s2(1250.0), 4);
  EXPECT_EQ(acceleration_units_from_us_per_s2(1e9), 255);
  EXPECT_DOUBLE_EQ(us_per_s2_from_acceleration_units(4), 1250.0);
}

}  // namespace
}  // namespace avar::firmware_iface::maestro
