#include "avar/core/byte_order.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <random>

namespace avar {
namespace {

using Bytes4 = std::array<std::uint8_t, 4>;

TEST(ByteOrder, LittleEndianPutsTheLeastSignificantByteFirst) {
  Bytes4 b{};
  put_u16_le(b.data(), 0x1234);
  EXPECT_EQ(b, (Bytes4{0x34, 0x12, 0, 0}));
  put_u32_le(b.data(), 0x12345678);
  EXPECT_EQ(b, (Bytes4{0x78, 0x56, 0x34, 0x12}));
  put_i16_le(b.data(), -2);
  EXPECT_EQ(b, (Bytes4{0xFE, 0xFF, 0x34, 0x12}));
  put_i32_le(b.data(), -2);
  EXPECT_EQ(b, (Bytes4{0xFE, 0xFF, 0xFF, 0xFF}));
  put_f32_le(b.data(), 1.0f);  // IEEE 754 binary32: 0x3F800000
  EXPECT_EQ(b, (Bytes4{0x00, 0x00, 0x80, 0x3F}));
  put_le(b.data(), 0xAABBCCDD, 3);
  EXPECT_EQ(b, (Bytes4{0xDD, 0xCC, 0xBB, 0x3F}));
}

TEST(ByteOrder, BigEndianPutsTheMostSignificantByteFirst) {
  Bytes4 b{};
  put_u16_be(b.data(), 0x1234);
  EXPECT_EQ(b, (Bytes4{0x12, 0x34, 0, 0}));
  put_u32_be(b.data(), 0x12345678);
  EXPECT_EQ(b, (Bytes4{0x12, 0x34, 0x56, 0x78}));
  put_i16_be(b.data(), -2);
  EXPECT_EQ(b, (Bytes4{0xFF, 0xFE, 0x56, 0x78}));
  put_i32_be(b.data(), -2);
  EXPECT_EQ(b, (Bytes4{0xFF, 0xFF, 0xFF, 0xFE}));
  put_f32_be(b.data(), -2.5f);  // 0xC0200000
  EXPECT_EQ(b, (Bytes4{0xC0, 0x20, 0x00, 0x00}));
  put_be(b.data(), 0xAABBCCDD, 3);
  EXPECT_EQ(b, (Bytes4{0xBB, 0xCC, 0xDD, 0x00}));
}

TEST(ByteOrder, GetsReadWhatTheDocumentsWrite) {
  const Bytes4 b{0x78, 0x56, 0x34, 0x12};
  EXPECT_EQ(get_u16_le(b.data()), 0x5678);
  EXPECT_EQ(get_u32_le(b.data()), 0x12345678u);
  EXPECT_EQ(get_u16_be(b.data()), 0x7856);
  EXPECT_EQ(get_u32_be(b.data()), 0x78563412u);
  EXPECT_EQ(get_le(b.data(), 3), 0x345678u);
  EXPECT_EQ(get_be(b.data(), 3), 0x785634u);
  EXPECT_EQ(get_le(b.data(), 0), 0u);
  const Bytes4 minus{0xFF, 0xFE, 0xFF, 0xFF};
  EXPECT_EQ(get_i16_le(minus.data()), -257);
  EXPECT_EQ(get_i16_be(minus.data()), -2);
  EXPECT_EQ(get_i32_le(minus.data()), -257);
  EXPECT_EQ(get_i32_be(minus.data()), -65537);
  const Bytes4 one{0x00, 0x00, 0x80, 0x3F};
  EXPECT_EQ(get_f32_le(one.data()), 1.0f);
  const Bytes4 minus_two_and_a_half{0xC0, 0x20, 0x00, 0x00};
  EXPECT_EQ(get_f32_be(minus_two_and_a_half.data()), -2.5f);
}

TEST(ByteOrder, ExtremesSurviveTheRoundTrip) {
  Bytes4 b{};
  put_i16_le(b.data(), std::numeric_limits<std::int16_t>::min());
  EXPECT_EQ(get_i16_le(b.data()), std::numeric_limits<std::int16_t>::min());
  put_i32_be(b.data(), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(get_i32_be(b.data()), std::numeric_limits<std::int32_t>::min());
  put_u32_le(b.data(), 0xFFFFFFFF);
  EXPECT_EQ(get_u32_le(b.data()), 0xFFFFFFFFu);
  put_f32_le(b.data(), std::numeric_limits<float>::infinity());
  EXPECT_EQ(get_f32_le(b.data()), std::numeric_limits<float>::infinity());
}

TEST(ByteOrder, RandomValuesRoundTripBothWays) {
  const std::uint64_t seed = 20261203;
  std::mt19937_64 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  Bytes4 b{};
  for (int i = 0; i < 10000; ++i) {
    const auto v = static_cast<std::uint32_t>(rng());
    put_u32_le(b.data(), v);
    ASSERT_EQ(get_u32_le(b.data()), v);
    ASSERT_EQ(get_u32_be(b.data()), (v >> 24) | ((v >> 8) & 0xFF00) | ((v << 8) & 0xFF0000) | (v << 24));
    put_u32_be(b.data(), v);
    ASSERT_EQ(get_u32_be(b.data()), v);
    put_i16_be(b.data(), static_cast<std::int16_t>(v));
    ASSERT_EQ(get_i16_be(b.data()), static_cast<std::int16_t>(v));
  }
}

constexpr std::uint32_t packed_at_compile_time() {
  std::uint8_t b[4]{};
  put_u32_be(b, 0xCAFEF00D);
  return get_u32_le(b);
}
static_assert(packed_at_compile_time() == 0x0DF0FECA);
static_assert(get_f32_be(std::array<std::uint8_t, 4>{0x3F, 0x80, 0, 0}.data()) == 1.0f);

}  // namespace
}  // namespace avar
