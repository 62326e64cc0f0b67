// Golden bytes from shared/protocols/pololu-maestro.md, section 7 (vectors M1..M12), the
// command table of section 3 in both framings, CRC-7 properties, saturation, invalid arguments
// and the unit conversions of the guide's worked numbers.
#include "avar/firmware_iface/maestro_codec.hpp"

#include <gtest/gtest.h>

#include "../support/encode.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace avar::firmware_iface::maestro {
namespace {

using avar::testing::Bytes;

template <class F>
Bytes encode(F&& f) {
  return avar::testing::encode_into<kMaxPacketSize>(f);
}

const Framing kCompact{};
const Framing kPololu12{true, 12, false};

TEST(MaestroCodec, M1_M2_CompactSetTarget) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 6000); }), (Bytes{0x84, 0x00, 0x70, 0x2E}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 2, 6000); }), (Bytes{0x84, 0x02, 0x70, 0x2E}));
}

TEST(MaestroCodec, M3_PololuSetTarget) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kPololu12, 0, 6000); }),
            (Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E}));
}

TEST(MaestroCodec, M4_MiniSsc) {
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 0, 127); }), (Bytes{0xFF, 0x00, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 254, 254); }), (Bytes{0xFF, 0xFE, 0xFE}));
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 0, 255); }), Bytes{});  // 0xFF is the start byte
  EXPECT_EQ(encode([](auto o) { return encode_mini_ssc(o, 255, 0); }), Bytes{});
}

TEST(MaestroCodec, M5_SetMultipleTargets) {
  const std::array<std::uint16_t, 2> targets{0, 6000};
  EXPECT_EQ(encode([&](auto o) { return encode_set_multiple_targets(o, kCompact, 3, targets); }),
            (Bytes{0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E}));
  EXPECT_EQ(encode([&](auto o) { return encode_set_multiple_targets(o, kPololu12, 3, targets); }),
            (Bytes{0xAA, 0x0C, 0x1F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E}));
}

TEST(MaestroCodec, M6_SetSpeed) {
  EXPECT_EQ(encode([](auto o) { return encode_set_speed(o, kCompact, 5, 140); }), (Bytes{0x87, 0x05, 0x0C, 0x01}));
  EXPECT_EQ(encode([](auto o) { return encode_set_speed(o, kPololu12, 5, 140); }),
            (Bytes{0xAA, 0x0C, 0x07, 0x05, 0x0C, 0x01}));
}

TEST(MaestroCodec, M7_GetPositionPololuWithCrc) {
  EXPECT_EQ(encode([](auto o) { return encode_get_position(o, Framing{true, 1, true}, 0); }),
            (Bytes{0xAA, 0x01, 0x10, 0x00, 0x6B}));
}

TEST(MaestroCodec, M8_M9_M10_Crc7) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, Framing{false, 12, true}, 0, 6000); }),
            (Bytes{0x84, 0x00, 0x70, 0x2E, 0x2B}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, Framing{true, 12, true}, 0, 6000); }),
            (Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E, 0x22}));
  EXPECT_EQ(crc7(std::array<std::uint8_t, 2>{0x83, 0x01}), 0x17);
  EXPECT_EQ(crc7(std::array<std::uint8_t, 4>{0xAA, 0x01, 0x10, 0x00}), 0x6B);
  EXPECT_EQ(crc7(std::span<const std::uint8_t>{}), 0);
}

TEST(MaestroCodec, M11_PulseEnds) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 4000); }), (Bytes{0x84, 0x00, 0x20, 0x1F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 8000); }), (Bytes{0x84, 0x00, 0x40, 0x3E}));
}

TEST(MaestroCodec, M12_PositionReply) {
  EXPECT_EQ(decode_position_reply(std::array<std::uint8_t, 2>{0x70, 0x17}), 6000);
  EXPECT_EQ(decode_position_reply(std::array<std::uint8_t, 2>{0xFF, 0xFF}), 0xFFFF);  // full 8-bit bytes
}

TEST(MaestroCodec, EveryCommandInBothFramings) {
  EXPECT_EQ(encode([](auto o) { return encode_set_acceleration(o, kCompact, 1, 4); }), (Bytes{0x89, 0x01, 0x04, 0x00}));
  EXPECT_EQ(encode([](auto o) { return encode_set_acceleration(o, kPololu12, 1, 4); }),
            (Bytes{0xAA, 0x0C, 0x09, 0x01, 0x04, 0x00}));
  EXPECT_EQ(encode([](auto o) { return encode_get_position(o, kCompact, 23); }), (Bytes{0x90, 0x17}));
  EXPECT_EQ(encode([](auto o) { return encode_get_position(o, kPololu12, 23); }), (Bytes{0xAA, 0x0C, 0x10, 0x17}));
  EXPECT_EQ(encode([](auto o) { return encode_get_moving_state(o, kCompact); }), Bytes{0x93});
  EXPECT_EQ(encode([](auto o) { return encode_get_moving_state(o, kPololu12); }), (Bytes{0xAA, 0x0C, 0x13}));
  EXPECT_EQ(encode([](auto o) { return encode_get_errors(o, kCompact); }), Bytes{0xA1});
  EXPECT_EQ(encode([](auto o) { return encode_get_errors(o, kPololu12); }), (Bytes{0xAA, 0x0C, 0x21}));
  EXPECT_EQ(encode([](auto o) { return encode_go_home(o, kCompact); }), Bytes{0xA2});
  EXPECT_EQ(encode([](auto o) { return encode_go_home(o, kPololu12); }), (Bytes{0xAA, 0x0C, 0x22}));
  // The CRC byte is the CRC-7 of everything before it.
  const Bytes with_crc = encode([](auto o) { return encode_go_home(o, Framing{true, 127, true}); });
  ASSERT_EQ(with_crc.size(), 4u);
  EXPECT_EQ(with_crc[1], 127);
  EXPECT_EQ(with_crc[3], crc7(std::span(with_crc).first(3)));
}

TEST(MaestroCodec, CompactFormIgnoresTheDeviceNumber) {
  EXPECT_EQ(encode([](auto o) { return encode_get_errors(o, Framing{false, 200, false}); }), Bytes{0xA1});
  EXPECT_EQ(encode([](auto o) { return encode_get_errors(o, Framing{true, 128, false}); }), Bytes{});
}

TEST(MaestroCodec, RepliesDecode) {
  EXPECT_EQ(decode_errors_reply(std::array<std::uint8_t, 2>{0x10, 0x01}), kSerialProtocolError | kScriptProgramCounterError);
  EXPECT_TRUE(decode_moving_state_reply(std::array<std::uint8_t, 1>{0x01}));
  EXPECT_FALSE(decode_moving_state_reply(std::array<std::uint8_t, 1>{0x00}));
}

TEST(MaestroCodec, ErrorNamesFollowTheRegisterTable) {
  EXPECT_EQ(describe_errors(0), "none");
  EXPECT_EQ(describe_errors(kSerialSignalError), "serial signal error");
  EXPECT_EQ(describe_errors(kSerialOverrunError), "serial overrun error");
  EXPECT_EQ(describe_errors(kSerialRxBufferFull), "serial RX buffer full");
  EXPECT_EQ(describe_errors(kSerialTimeout), "serial timeout");
  EXPECT_EQ(describe_errors(kScriptStackError), "script stack error");
  EXPECT_EQ(describe_errors(kScriptCallStackError), "script call stack error");
  EXPECT_EQ(describe_errors(kScriptProgramCounterError), "script program counter error");
  EXPECT_EQ(describe_errors(kSerialCrcError | kSerialProtocolError), "serial CRC error, serial protocol error");
  EXPECT_EQ(describe_errors(0x8200), "error bit 9, error bit 15");
}

TEST(MaestroCodec, ValuesSaturateNeverWrap) {
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 0xFFFF); }), (Bytes{0x84, 0x00, 0x7F, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_target(o, kCompact, 0, 0x4000); }), (Bytes{0x84, 0x00, 0x7F, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_speed(o, kCompact, 0, 0x8000); }), (Bytes{0x87, 0x00, 0x7F, 0x7F}));
  EXPECT_EQ(encode([](auto o) { return encode_set_acceleration(o, kCompact, 0, 1000); }), (Bytes{0x89, 0x00, 0x7F, 0x01}));
  const std::array<std::uint16_t, 2> big{0xFFFF, 6000};
  EXPECT_EQ(encode([&](auto o) { return encode_set_multiple_targets(o, kCompact, 0, big); }),
            (Bytes{0x9F, 0x02, 0x00, 0x7F, 0x7F, 0x70, 0x2E}));
}

TEST(MaestroCodec, FourteenBitValuesRoundTripOverRandomArguments) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> channel(0, kMaxChannels - 1);
  std::uniform_int_distribution<int> value(0, 0xFFFF);
  std::uniform_int_distribution<int> device(0, 127);
  for (int i = 0; i < 5000; ++i) {
    const Framing f{(i & 1) != 0, static_cast<std::uint8_t>(device(rng)), (i & 2) != 0};
    const auto ch = static_cast<std::uint8_t>(channel(rng));
    const auto v = static_cast<std::uint16_t>(value(rng));
    const Bytes p = encode([&](auto o) { return encode_set_target(o, f, ch, v); });
    const std::size_t head = f.pololu ? 3 : 1;
    ASSERT_EQ(p.size(), head + 3 + (f.crc ? 1 : 0));
    // Only the first byte has its top bit set; the rest are 7-bit data bytes.
    EXPECT_TRUE(p[0] & 0x80);
    for (std::size_t k = 1; k < p.size(); ++k) ASSERT_LT(p[k], 0x80) << "byte " << k;
    EXPECT_EQ(p[head], ch);
    EXPECT_EQ(p[head + 1] | (p[head + 2] << 7), std::min<int>(v, kMaxValue));
    if (f.crc) {
      EXPECT_EQ(p.back(), crc7(std::span(p).first(p.size() - 1)));
    }
  }
}

TEST(MaestroCodec, Crc7IsLinearAndCatchesEverySingleBitError) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(1, 54);
  for (int i = 0; i < 2000; ++i) {
    Bytes a(static_cast<std::size_t>(length(rng)));
    Bytes b(a.size());
    Bytes x(a.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      a[k] = static_cast<std::uint8_t>(byte(rng));
      b[k] = static_cast<std::uint8_t>(byte(rng));
      x[k] = static_cast<std::uint8_t>(a[k] ^ b[k]);
    }
    // Initial value 0 and no final XOR: the CRC of a XOR b is the XOR of the CRCs.
    ASSERT_EQ(crc7(x), crc7(a) ^ crc7(b));
    ASSERT_LT(crc7(a), 0x80);
    Bytes flipped = a;
    const auto bit = static_cast<std::size_t>(std::uniform_int_distribution<int>(0, static_cast<int>(8 * a.size()) - 1)(rng));
    flipped[bit / 8] = static_cast<std::uint8_t>(flipped[bit / 8] ^ (1u << (bit % 8)));
    ASSERT_NE(crc7(flipped), crc7(a)) << "bit " << bit;
  }
}

TEST(MaestroCodec, InvalidArgumentsWriteNothing) {
  std::array<std::uint8_t, kMaxPacketSize> buf{};
  EXPECT_EQ(encode_set_target(buf, kCompact, 24, 6000), 0u);
  EXPECT_EQ(encode_set_target(buf, kCompact, 255, 6000), 0u);
  EXPECT_EQ(encode_set_speed(buf, kCompact, 24, 1), 0u);
  EXPECT_EQ(encode_set_acceleration(buf, kCompact, 24, 1), 0u);
  EXPECT_EQ(encode_get_position(buf, kCompact, 24), 0u);
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 0, {}), 0u);
  const std::array<std::uint16_t, 3> three{6000, 6000, 6000};
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 22, three), 0u);  // would reach channel 24
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 21, three), 9u);  // ends at channel 23
  const std::array<std::uint16_t, 25> too_many{};
  EXPECT_EQ(encode_set_multiple_targets(buf, kCompact, 0, too_many), 0u);
  EXPECT_EQ(encode_set_target(buf, Framing{true, 128, false}, 0, 6000), 0u);
  EXPECT_EQ(encode_mini_ssc(buf, 0, 255), 0u);
}

TEST(MaestroCodec, LargestPacketFillsTheStaticBuffer) {
  std::array<std::uint8_t, kMaxPacketSize> buf{};
  const std::array<std::uint16_t, 24> all{};
  EXPECT_EQ(encode_set_multiple_targets(buf, Framing{true, 12, true}, 0, all), kMaxPacketSize);
  // The throughput check of the notes: 24 targets in the Pololu form are 53 bytes without CRC.
  EXPECT_EQ(encode_set_multiple_targets(buf, Framing{true, 12, false}, 0, all), 53u);
}

TEST(MaestroCodec, BuffersOneByteShortWriteNothing) {
  struct Case {
    const char* name;
    std::size_t size;
    std::size_t (*encode)(std::span<std::uint8_t>);
  };
  static const std::array<std::uint16_t, 24> all{};
  const Case cases[] = {
      {"set target", 7, [](std::span<std::uint8_t> o) { return encode_set_target(o, Framing{true, 12, true}, 0, 6000); }},
      {"set multiple", kMaxPacketSize,
       [](std::span<std::uint8_t> o) { return encode_set_multiple_targets(o, Framing{true, 12, true}, 0, all); }},
      {"set speed", 4, [](std::span<std::uint8_t> o) { return encode_set_speed(o, Framing{}, 0, 1); }},
      {"set acceleration", 5, [](std::span<std::uint8_t> o) { return encode_set_acceleration(o, Framing{false, 12, true}, 0, 1); }},
      {"get position", 4, [](std::span<std::uint8_t> o) { return encode_get_position(o, Framing{true, 12, false}, 0); }},
      {"get moving state", 1, [](std::span<std::uint8_t> o) { return encode_get_moving_state(o, Framing{}); }},
      {"get errors", 4, [](std::span<std::uint8_t> o) { return encode_get_errors(o, Framing{true, 12, true}); }},
      {"go home", 2, [](std::span<std::uint8_t> o) { return encode_go_home(o, Framing{false, 12, true}); }},
      {"mini ssc", 3, [](std::span<std::uint8_t> o) { return encode_mini_ssc(o, 0, 127); }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::array<std::uint8_t, kMaxPacketSize> buf{};
    buf.fill(0x5A);
    EXPECT_EQ(c.encode(std::span(buf).first(c.size - 1)), 0u);
    for (std::uint8_t b : buf) ASSERT_EQ(b, 0x5A);
    EXPECT_EQ(c.encode(std::span(buf).first(c.size)), c.size);
  }
}

TEST(MaestroCodec, PulseWidthsInQuarterMicroseconds) {
  EXPECT_EQ(quarter_us_from_us(1500.0), 6000);
  EXPECT_EQ(quarter_us_from_us(1500.1), 6000);   // nearest quarter
  EXPECT_EQ(quarter_us_from_us(1500.13), 6001);
  EXPECT_EQ(quarter_us_from_us(1e9), kMaxValue);  // saturates
  EXPECT_EQ(quarter_us_from_us(-5), 0);
  EXPECT_EQ(quarter_us_from_us(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(quarter_us_from_us(std::numeric_limits<double>::infinity()), kMaxValue);
  EXPECT_DOUBLE_EQ(us_from_quarter_us(6001), 1500.25);
  for (int q = 0; q <= kMaxValue; ++q)
    ASSERT_EQ(quarter_us_from_us(us_from_quarter_us(static_cast<std::uint16_t>(q))), q);
}

TEST(MaestroCodec, SpeedUnitsFromTheGuide) {
  // Speed 140 = 3.5 µs/ms; speed 4 = 1 µs per 10 ms = 100 µs/s.
  EXPECT_DOUBLE_EQ(us_per_s_from_speed_units(140), 3500.0);
  EXPECT_DOUBLE_EQ(us_per_s_from_speed_units(140) / 1000.0, 3.5);
  EXPECT_EQ(speed_units_from_us_per_s(3500.0), 140);
  EXPECT_EQ(speed_units_from_us_per_s(100.0), 4);
  EXPECT_EQ(speed_units_from_us_per_s(124.9), 4);  // rounded down: never faster than asked
  // Speed 1: 1 ms -> 2 ms takes 40 s.
  EXPECT_DOUBLE_EQ(1000.0 / us_per_s_from_speed_units(1), 40.0);
  EXPECT_EQ(speed_units_from_us_per_s(1.0), 1);  // the slowest, never 0 = "unlimited"
  EXPECT_EQ(speed_units_from_us_per_s(0.0), 1);
  EXPECT_EQ(speed_units_from_us_per_s(-10.0), 1);
  EXPECT_EQ(speed_units_from_us_per_s(std::numeric_limits<double>::quiet_NaN()), 1);
  EXPECT_EQ(speed_units_from_us_per_s(1e12), kMaxValue);
  EXPECT_EQ(speed_units_from_us_per_s(std::numeric_limits<double>::infinity()), kMaxValue);
  EXPECT_DOUBLE_EQ(us_per_s_from_speed_units(0), 0.0);
}

TEST(MaestroCodec, AccelerationUnitsFromTheGuide) {
  // 312.5 µs/s² per unit; acceleration 4 = 1250 µs/s².
  EXPECT_DOUBLE_EQ(us_per_s2_from_acceleration_units(1), 312.5);
  EXPECT_DOUBLE_EQ(us_per_s2_from_acceleration_units(4), 1250.0);
  EXPECT_EQ(acceleration_units_from_us_per_s2(1250.0), 4);
  EXPECT_EQ(acceleration_units_from_us_per_s2(1249.0), 3);
  EXPECT_EQ(acceleration_units_from_us_per_s2(1.0), 1);
  EXPECT_EQ(acceleration_units_from_us_per_s2(-1.0), 1);
  EXPECT_EQ(acceleration_units_from_us_per_s2(std::numeric_limits<double>::quiet_NaN()), 1);
  EXPECT_EQ(acceleration_units_from_us_per_s2(1e9), kMaxAcceleration);
  EXPECT_DOUBLE_EQ(us_per_s2_from_acceleration_units(0), 0.0);
}

}  // namespace
}  // namespace avar::firmware_iface::maestro
