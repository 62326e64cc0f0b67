// Golden bytes from ../shared/protocols/feetech-sts.md, section 7 (vectors F1..F9), round trips
// and the resynchronising decoder.
#include "avar/firmware_iface/feetech_codec.hpp"

#include <gtest/gtest.h>

#include "../support/encode.hpp"

#include <array>
#include <random>
#include <vector>

namespace avar::firmware_iface::feetech {
namespace {

using avar::testing::Bytes;

template <class F>
Bytes encode(F&& f) {
  return avar::testing::encode_into<kMaxPacketSize>(f);
}

TEST(FeetechCodec, F1_Ping) {
  EXPECT_EQ(encode([](auto o) { return encode_ping(o, 1); }), (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB}));
}

TEST(FeetechCodec, F2_ReadPresentPosition) {
  EXPECT_EQ(encode([](auto o) { return encode_read(o, 1, kPresentPosition, 2); }),
            (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x02, 0x38, 0x02, 0xBE}));
}

TEST(FeetechCodec, F3_StatusReplyDecodesToPosition2048OnSts) {
  const Bytes reply{0xFF, 0xFF, 0x01, 0x04, 0x00, 0x00, 0x08, 0xF2};
  Packet p;
  std::size_t used = 0;
  ASSERT_EQ(decode_packet(reply, &p, &used), DecodeResult::ok);
  EXPECT_EQ(used, reply.size());
  EXPECT_EQ(p.id, 1);
  EXPECT_EQ(p.code, 0);  // error byte
  ASSERT_EQ(p.params.size(), 2u);
  EXPECT_EQ(get_word(Series::sts, p.params), 2048);
  EXPECT_EQ(get_word(Series::scs, p.params), 8);  // the same bytes read big-endian
  const std::uint8_t pos[2] = {0x00, 0x08};
  EXPECT_EQ(encode([&](auto o) { return encode_packet(o, 1, 0, pos); }), reply);
}

TEST(FeetechCodec, F4_F5_WriteGoalPositionInEachSeriesByteOrder) {
  EXPECT_EQ(encode([](auto o) { return encode_write_word(o, Series::sts, 1, kGoalPosition, 2048); }),
            (Bytes{0xFF, 0xFF, 0x01, 0x05, 0x03, 0x2A, 0x00, 0x08, 0xC4}));
  EXPECT_EQ(encode([](auto o) { return encode_write_word(o, Series::scs, 1, kGoalPosition, 512); }),
            (Bytes{0xFF, 0xFF, 0x01, 0x05, 0x03, 0x2A, 0x02, 0x00, 0xCA}));
}

TEST(FeetechCodec, F6_PositionSpeedBlockAt41) {
  std::array<std::uint8_t, 7> block{50};
  put_word(Series::sts, std::span<std::uint8_t, 2>(&block[1], 2), 2048);
  put_word(Series::sts, std::span<std::uint8_t, 2>(&block[3], 2), 0);
  put_word(Series::sts, std::span<std::uint8_t, 2>(&block[5], 2), 1000);
  EXPECT_EQ(encode([&](auto o) { return encode_write(o, 1, kAcceleration, block); }),
            (Bytes{0xFF, 0xFF, 0x01, 0x0A, 0x03, 0x29, 0x32, 0x00, 0x08, 0x00, 0x00, 0xE8, 0x03, 0xA3}));
}

TEST(FeetechCodec, F7_SyncWriteGoalPositions) {
  const std::uint8_t ids[2] = {1, 2};
  const std::uint16_t goals[2] = {2048, 1024};
  EXPECT_EQ(encode([&](auto o) { return encode_sync_write_words(o, Series::sts, kGoalPosition, ids, goals); }),
            (Bytes{0xFF, 0xFF, 0xFE, 0x0A, 0x83, 0x2A, 0x02, 0x01, 0x00, 0x08, 0x02, 0x00, 0x04, 0x39}));
  EXPECT_EQ(sync_write_size(2, 2), 14u);
  EXPECT_EQ(sync_write_size(2, 16), 56u);  // the README's table
}

TEST(FeetechCodec, F8_SyncReadPresentPosition) {
  const std::uint8_t ids[2] = {1, 2};
  EXPECT_EQ(encode([&](auto o) { return encode_sync_read(o, kPresentPosition, 2, ids); }),
            (Bytes{0xFF, 0xFF, 0xFE, 0x06, 0x82, 0x38, 0x02, 0x01, 0x02, 0x3C}));
  EXPECT_EQ(sync_read_size(16) + 16 * status_size(2), 24u + 128u);
}

TEST(FeetechCodec, F9_SignMagnitude) {
  const std::uint16_t raw = to_sign_magnitude(-100, kPositionSignBit);
  EXPECT_EQ(raw, 0x8064);
  std::array<std::uint8_t, 2> wire{};
  put_word(Series::sts, wire, raw);
  EXPECT_EQ(wire, (std::array<std::uint8_t, 2>{0x64, 0x80}));
  EXPECT_EQ(from_sign_magnitude(0x8064, kPositionSignBit), -100);
  // Load has its sign in bit 10; magnitudes saturate instead of spilling into the sign.
  EXPECT_EQ(to_sign_magnitude(-500, kLoadSignBit), 0x400 | 500);
  EXPECT_EQ(from_sign_magnitude(0x400 | 500, kLoadSignBit), -500);
  EXPECT_EQ(to_sign_magnitude(5000, kLoadSignBit), 1023);
  EXPECT_EQ(to_sign_magnitude(-40000, kPositionSignBit), 0xFFFF);
  // Positions: sign-magnitude on STS, unsigned on SCS.
  EXPECT_EQ(position_word(Series::sts, -100), 0x8064);
  EXPECT_EQ(position_from_word(Series::sts, 0x8064), -100);
  EXPECT_EQ(position_word(Series::scs, -100), 0);
  EXPECT_EQ(position_word(Series::scs, 1023), 1023);
  EXPECT_EQ(position_from_word(Series::scs, 0x8064), 0x8064);
}

TEST(FeetechCodec, RejectsWhatCannotBeSent) {
  std::array<std::uint8_t, 5> tiny{};
  EXPECT_EQ(encode_ping(tiny, 1), 0u);
  std::array<std::uint8_t, kMaxPacketSize> buf{};
  EXPECT_EQ(encode_ping(buf, 0xFF), 0u);
  EXPECT_EQ(encode_read(buf, kBroadcastId, 56, 2), 0u);
  EXPECT_EQ(encode_read(buf, 1, 56, 0), 0u);
  const std::uint8_t bad_ids[2] = {1, kBroadcastId};
  const std::uint16_t v[2] = {1, 2};
  EXPECT_EQ(encode_sync_write_words(buf, Series::sts, kGoalPosition, bad_ids, v), 0u);
  EXPECT_EQ(encode_sync_read(buf, kPresentPosition, 2, bad_ids), 0u);
  std::array<std::uint8_t, 100> many_ids{};
  std::array<std::uint16_t, 100> many_values{};
  EXPECT_EQ(encode_sync_write_words(buf, Series::sts, kGoalPosition, many_ids, many_values), 0u);  // > 255 length
}

TEST(FeetechCodec, DecoderResynchronisesPastNoiseAndBadChecksums) {
  // noise, a corrupted status, FF FF FF (extra FF), then a good one
  Bytes in{0x12, 0x34, 0xFF, 0xFF, 0x01, 0x04, 0x00, 0x00, 0x08, 0xF3, 0xFF, 0xFF, 0xFF, 0x02, 0x02, 0x00, 0xFB};
  Packet p;
  std::size_t used = 0;
  std::span<const std::uint8_t> rest(in);
  ASSERT_EQ(decode_packet(rest, &p, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 2u);
  rest = rest.subspan(used);
  ASSERT_EQ(decode_packet(rest, &p, &used), DecodeResult::bad_checksum);
  EXPECT_EQ(used, 8u);
  rest = rest.subspan(used);
  ASSERT_EQ(decode_packet(rest, &p, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 1u);
  rest = rest.subspan(used);
  ASSERT_EQ(decode_packet(rest, &p, &used), DecodeResult::ok);
  EXPECT_EQ(p.id, 2);
  EXPECT_EQ(rest.size(), used);
  // Partial input waits; a lone trailing FF is kept.
  const Bytes partial{0xFF, 0xFF, 0x01, 0x04, 0x00};
  EXPECT_EQ(decode_packet(partial, &p, &used), DecodeResult::need_more);
  EXPECT_EQ(used, 0u);
  const Bytes trailing{0x00, 0xFF};
  EXPECT_EQ(decode_packet(trailing, &p, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 1u);
  // A length below 2 cannot be.
  const Bytes short_len{0xFF, 0xFF, 0x01, 0x01, 0x00, 0x00};
  EXPECT_EQ(decode_packet(short_len, &p, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 1u);
}

TEST(FeetechCodec, RandomSyncWritesRoundTripInBothSeries) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const Series series = trial % 2 ? Series::sts : Series::scs;
    const std::size_t n = std::uniform_int_distribution<std::size_t>(1, 40)(rng);
    std::vector<std::uint8_t> ids(n);
    std::vector<std::uint16_t> values(n);
    for (std::size_t i = 0; i < n; ++i) {
      ids[i] = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, kMaxId)(rng));
      values[i] = to_sign_magnitude(std::uniform_int_distribution<int>(-32767, 32767)(rng), kPositionSignBit);
    }
    const Bytes packet = encode([&](auto o) { return encode_sync_write_words(o, series, kGoalPosition, ids, values); });
    ASSERT_EQ(packet.size(), sync_write_size(2, n));
    Packet p;
    std::size_t used = 0;
    ASSERT_EQ(decode_packet(packet, &p, &used), DecodeResult::ok);
    ASSERT_EQ(p.code, kSyncWrite);
    ASSERT_EQ(p.params[0], kGoalPosition);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(p.params[2 + 3 * i], ids[i]);
      EXPECT_EQ(get_word(series, p.params.subspan(3 + 3 * i, 2)), values[i]);
    }
    // Any single flipped bit after the header is caught by the checksum or the framing.
    Bytes corrupt = packet;
    const std::size_t at = std::uniform_int_distribution<std::size_t>(4, corrupt.size() - 1)(rng);
    corrupt[at] ^= static_cast<std::uint8_t>(1u << std::uniform_int_distribution<int>(0, 7)(rng));
    EXPECT_NE(decode_packet(corrupt, &p, &used), DecodeResult::ok);
  }
}

TEST(FeetechCodec, DescribesErrorBits) {
  EXPECT_EQ(describe_error(0), "none");
  EXPECT_EQ(describe_error(kErrorOverheat | kErrorOverload), "overheat, overload");
}

}  // namespace
}  // namespace avar::firmware_iface::feetech
