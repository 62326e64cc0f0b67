// Golden bytes from ../shared/protocols/dynamixel-2.md, section 7 (vectors D1..D17).
#include "avar/firmware_iface/dynamixel_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace avar::firmware_iface::dynamixel {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <class F>
Bytes encode(F&& f) {
  std::array<std::uint8_t, 512> buf{};
  const std::size_t n = f(std::span<std::uint8_t>(buf));
  return Bytes(buf.begin(), buf.begin() + static_cast<long>(n));
}

TEST(DynamixelCodec, D1_D3_Ping) {
  EXPECT_EQ(encode([](auto o) { return encode_ping(o, 1); }), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E}));
  EXPECT_EQ(encode([](auto o) { return encode_ping(o, kBroadcastId); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x03, 0x00, 0x01, 0x31, 0x42}));
}

TEST(DynamixelCodec, D4_D6_D16_D17_ReadAndWrite) {
  EXPECT_EQ(encode([](auto o) { return encode_read(o, 1, kPresentPosition, 4); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15}));
  const Bytes p512{0x00, 0x02, 0x00, 0x00};
  EXPECT_EQ(encode([&](auto o) { return encode_write(o, 1, kGoalPosition, p512); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x03, 0x74, 0x00, 0x00, 0x02, 0x00, 0x00, 0xCA, 0x89}));
  const Bytes p2048{0x00, 0x08, 0x00, 0x00};
  EXPECT_EQ(encode([&](auto o) { return encode_write(o, 1, kGoalPosition, p2048); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x03, 0x74, 0x00, 0x00, 0x08, 0x00, 0x00, 0x42, 0x89}));
  const Bytes on{0x01};
  EXPECT_EQ(encode([&](auto o) { return encode_write(o, 1, kTorqueEnable, on); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x06, 0x00, 0x03, 0x40, 0x00, 0x01, 0xDB, 0x66}));
}

TEST(DynamixelCodec, D8_D9_D10_ActionRebootFactoryReset) {
  EXPECT_EQ(encode([](auto o) { return encode_action(o, 1); }), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x05, 0x02, 0xCE}));
  EXPECT_EQ(encode([](auto o) { return encode_reboot(o, 1); }), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x08, 0x2F, 0x4E}));
  EXPECT_EQ(encode([](auto o) { return encode_factory_reset(o, 1, 0x01); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x06, 0x01, 0xA1, 0xE6}));
  EXPECT_TRUE(encode([](auto o) { return encode_factory_reset(o, 1, 0x07); }).empty());
}

TEST(DynamixelCodec, D11_D12_SyncReadAndSyncWrite) {
  const Bytes ids{1, 2};
  EXPECT_EQ(encode([&](auto o) { return encode_sync_read(o, kPresentPosition, 4, ids); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x09, 0x00, 0x82, 0x84, 0x00, 0x04, 0x00, 0x01, 0x02, 0xCE, 0xFA}));
  const std::vector<std::int32_t> values{150, 170};
  EXPECT_EQ(encode([&](auto o) { return encode_sync_write_u32(o, kGoalPosition, ids, values); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x11, 0x00, 0x83, 0x74, 0x00, 0x04, 0x00, 0x01, 0x96, 0x00, 0x00, 0x00, 0x02,
                   0xAA, 0x00, 0x00, 0x00, 0x82, 0x87}));
  // 14 + 5N bytes for N servos, as the wire-time table says.
  std::vector<std::uint8_t> sixteen(16);
  std::vector<std::int32_t> v16(16, 2048);
  for (int i = 0; i < 16; ++i) sixteen[i] = static_cast<std::uint8_t>(i + 1);
  EXPECT_EQ(encode([&](auto o) { return encode_sync_write_u32(o, kGoalPosition, sixteen, v16); }).size(), 94u);
}

TEST(DynamixelCodec, D13_D14_RawInstructionsBuildBulkPackets) {
  const Bytes bulk_read{0x01, 0x90, 0x00, 0x02, 0x00, 0x02, 0x92, 0x00, 0x01, 0x00};
  EXPECT_EQ(encode([&](auto o) { return encode_instruction(o, kBroadcastId, kBulkRead, bulk_read); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x0D, 0x00, 0x92, 0x01, 0x90, 0x00, 0x02, 0x00, 0x02, 0x92, 0x00, 0x01, 0x00, 0x1A,
                   0x05}));
  const Bytes bulk_write{0x01, 0x20, 0x00, 0x02, 0x00, 0xA0, 0x00, 0x02, 0x1F, 0x00, 0x01, 0x00, 0x50};
  EXPECT_EQ(encode([&](auto o) { return encode_instruction(o, kBroadcastId, kBulkWrite, bulk_write); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x10, 0x00, 0x93, 0x01, 0x20, 0x00, 0x02, 0x00, 0xA0, 0x00, 0x02, 0x1F, 0x00, 0x01,
                   0x00, 0x50, 0xB7, 0x68}));
}

TEST(DynamixelCodec, D15_ByteStuffingCountsInTheLengthAndTheCrc) {
  const Bytes data{0xFF, 0xFF, 0xFD, 0x00};
  EXPECT_EQ(encode([&](auto o) { return encode_write(o, 1, kGoalPosition, data); }),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x0A, 0x00, 0x03, 0x74, 0x00, 0xFF, 0xFF, 0xFD, 0xFD, 0x00, 0x21, 0xE7}));
}

TEST(DynamixelCodec, D2_D5_D7_StatusPacketsDecode) {
  std::array<std::uint8_t, 64> scratch{};
  Status s;
  std::size_t used = 0;
  const Bytes d2{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D};
  ASSERT_EQ(decode_status(d2, scratch, &s, &used), DecodeResult::ok);
  EXPECT_EQ(used, d2.size());
  EXPECT_EQ(s.id, 1);
  EXPECT_EQ(read_u16(s.params), 1030);  // XM430-W210
  EXPECT_EQ(s.params[2], 38);           // firmware
  const Bytes d5{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55, 0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0};
  ASSERT_EQ(decode_status(d5, scratch, &s, &used), DecodeResult::ok);
  EXPECT_EQ(read_i32(s.params), 166);
  const Bytes d7{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x00, 0xA1, 0x0C};
  ASSERT_EQ(decode_status(d7, scratch, &s, &used), DecodeResult::ok);
  EXPECT_TRUE(s.params.empty());
  EXPECT_FALSE(s.alert());
}

TEST(DynamixelCodec, DecoderResynchronisesAndReportsCrcErrors) {
  std::array<std::uint8_t, 64> scratch{};
  Status s;
  std::size_t used = 0;
  Bytes stream{0x12, 0xFF, 0x34};
  const Bytes d7{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x00, 0xA1, 0x0C};
  stream.insert(stream.end(), d7.begin(), d7.end());
  ASSERT_EQ(decode_status(stream, scratch, &s, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 3u);  // the noise before the header
  ASSERT_EQ(decode_status(std::span(stream).subspan(used), scratch, &s, &used), DecodeResult::ok);
  EXPECT_EQ(decode_status(std::span(d7).first(6), scratch, &s, &used), DecodeResult::need_more);
  Bytes corrupt = d7;
  corrupt[9] ^= 0x01;
  EXPECT_EQ(decode_status(corrupt, scratch, &s, &used), DecodeResult::bad_crc);
  EXPECT_EQ(used, corrupt.size());
  const Bytes instruction{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E};
  EXPECT_EQ(decode_status(instruction, scratch, &s, &used), DecodeResult::not_status);
}

TEST(DynamixelCodec, StuffedStatusParametersRoundTrip) {
  // A status packet carrying FF FF FD 00 (stuffed on the wire), built with the instruction
  // encoder as a device would, decodes back to the original bytes.
  std::array<std::uint8_t, 64> wire{};
  const Bytes params{0x00 /* error */, 0xFF, 0xFF, 0xFD, 0x00};
  const std::size_t n = encode_instruction(wire, 3, kStatus, params);
  ASSERT_GT(n, 0u);
  std::array<std::uint8_t, 64> scratch{};
  Status s;
  std::size_t used = 0;
  ASSERT_EQ(decode_status(std::span(wire.data(), n), scratch, &s, &used), DecodeResult::ok);
  EXPECT_EQ(Bytes(s.params.begin(), s.params.end()), (Bytes{0xFF, 0xFF, 0xFD, 0x00}));
}

TEST(DynamixelCodec, ErrorNames) {
  EXPECT_EQ(describe_processing_error(0x83), "CRC error");
  EXPECT_EQ(describe_hardware_error(0x24), "overheating, overload error");
  EXPECT_EQ(crc16(Bytes{}), 0);
}

}  // namespace
}  // namespace avar::firmware_iface::dynamixel
