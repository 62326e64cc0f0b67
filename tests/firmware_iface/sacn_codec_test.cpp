#include "avar/firmware_iface/sacn_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

namespace avar::firmware_iface::sacn {
namespace {

constexpr Cid kSacnTestCid{0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x10};

std::vector<std::uint8_t> sacn_test_root(std::uint8_t length_low, std::uint8_t vector) {
  std::vector<std::uint8_t> b{0x00, 0x10,       0x00, 0x00,  // preamble, post-amble
                              0x41, 0x53,       0x43, 0x2D,  0x45, 0x31, 0x2E, 0x31, 0x37, 0x00, 0x00, 0x00,  // "ASC-E1.17"
                              0x70, length_low,                                                               // flags, length
                              0x00, 0x00,       0x00, vector};
  // One byte at a time: GCC 12 warns falsely (array-bounds) on a range insert here.
  for (const std::uint8_t c : kSacnTestCid) b.push_back(c);
  return b;
}

void sacn_test_name(std::vector<std::uint8_t>& b, std::string_view name) {
  std::array<std::uint8_t, 64> field{};
  std::copy(name.begin(), name.end(), field.begin());
  b.insert(b.end(), field.begin(), field.end());
}

TEST(SacnCodec, GoldenDataPacketFromTheE131Layout) {
  const std::array<std::uint8_t, 4> slots{0x00, 0x40, 0x80, 0xFF};
  DataHeader h;
  h.universe = 0x0102;
  h.priority = 150;
  h.sync_address = 0x0007;
  h.sequence = 0x2A;
  h.options = kPreviewData;
  std::array<std::uint8_t, kMaxDataPacketSize> out{};
  ASSERT_EQ(encode_data(out, Source{kSacnTestCid, "avar"}, h, slots), 130U);

  std::vector<std::uint8_t> expected = sacn_test_root(114, 0x04);             // 130 - 16, VECTOR_ROOT_E131_DATA
  const std::vector<std::uint8_t> framing{0x70, 92, 0x00, 0x00, 0x00, 0x02};  // 130 - 38, E131_DATA_PACKET
  expected.insert(expected.end(), framing.begin(), framing.end());
  sacn_test_name(expected, "avar");
  const std::vector<std::uint8_t> rest{150,                     // priority
                                       0x00, 0x07,              // synchronization address
                                       0x2A,                    // sequence
                                       0x80,                    // options: preview
                                       0x01, 0x02,              // universe
                                       0x70, 15,                // DMP flags, length 130 - 115
                                       0x02, 0xA1,              // SET_PROPERTY, address and data type
                                       0x00, 0x00, 0x00, 0x01,  // first address, increment
                                       0x00, 0x05,              // count: start code + 4
                                       0x00,                    // start code
                                       0x00, 0x40, 0x80, 0xFF};
  expected.insert(expected.end(), rest.begin(), rest.end());
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + 130), expected);

  // A full universe: the lengths every E1.31 capture shows.
  const std::vector<std::uint8_t> full(512, 0);
  ASSERT_EQ(encode_data(out, Source{kSacnTestCid, "avar"}, h, full), 638U);
  EXPECT_EQ(out[16], 0x72);
  EXPECT_EQ(out[17], 0x6E);
  EXPECT_EQ(out[38], 0x72);
  EXPECT_EQ(out[39], 0x58);
  EXPECT_EQ(out[115], 0x72);
  EXPECT_EQ(out[116], 0x0B);
  EXPECT_EQ(out[123], 0x02);
  EXPECT_EQ(out[124], 0x01);
}

TEST(SacnCodec, GoldenUniverseDiscoveryPacket) {
  const std::array<std::uint16_t, 3> universes{1, 2, 500};
  std::array<std::uint8_t, kMaxDiscoveryPacketSize> out{};
  ASSERT_EQ(encode_discovery(out, Source{kSacnTestCid, "avar"}, 0, 0, universes), 126U);
  std::vector<std::uint8_t> expected = sacn_test_root(110, 0x08);             // VECTOR_ROOT_E131_EXTENDED
  const std::vector<std::uint8_t> framing{0x70, 88, 0x00, 0x00, 0x00, 0x02};  // E131_EXTENDED_DISCOVERY
  expected.insert(expected.end(), framing.begin(), framing.end());
  sacn_test_name(expected, "avar");
  const std::vector<std::uint8_t> rest{0,    0,    0,    0,     // reserved
                                       0x70, 14,                // flags, length 126 - 112
                                       0x00, 0x00, 0x00, 0x01,  // UNIVERSE_LIST
                                       0,    0,                 // page, last page
                                       0x00, 0x01, 0x00, 0x02, 0x01, 0xF4};
  expected.insert(expected.end(), rest.begin(), rest.end());
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + 126), expected);

  std::array<std::uint16_t, 8> back{};
  const auto p = decode_discovery(std::span(out.data(), 126), back);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->source_name, "avar");
  ASSERT_EQ(p->universe_count, 3U);
  EXPECT_EQ(back[2], 500);
  const std::array<std::uint16_t, 2> unsorted{5, 4};
  EXPECT_EQ(encode_discovery(out, Source{kSacnTestCid, "avar"}, 0, 0, unsorted), 0U);
  EXPECT_EQ(encode_discovery(out, Source{kSacnTestCid, "avar"}, 1, 0, universes), 0U);
}

TEST(SacnCodec, MulticastGroupIs239_255_HiLo) {
  EXPECT_EQ(multicast_group(1), 0xEFFF0001U);
  EXPECT_EQ(multicast_group(0x0102), 0xEFFF0102U);
  EXPECT_EQ(multicast_group(kDiscoveryUniverse), 0xEFFFFAD6U);
}

TEST(SacnCodec, EncoderRefusesBadArguments) {
  std::array<std::uint8_t, kMaxDataPacketSize> out{};
  const std::array<std::uint8_t, 2> slots{1, 2};
  DataHeader h;
  h.universe = 0;
  EXPECT_EQ(encode_data(out, Source{}, h, slots), 0U);
  h.universe = 64000;
  EXPECT_EQ(encode_data(out, Source{}, h, slots), 0U);
  h.universe = 1;
  h.priority = 201;
  EXPECT_EQ(encode_data(out, Source{}, h, slots), 0U);
  h.priority = 200;
  const std::vector<std::uint8_t> too_many(513, 0);
  EXPECT_EQ(encode_data(out, Source{}, h, too_many), 0U);
  std::array<std::uint8_t, 127> small{};
  EXPECT_EQ(encode_data(small, Source{}, h, slots), 0U);
  // A name longer than 63 bytes is cut and stays terminated.
  const std::string long_name(80, 'x');
  ASSERT_EQ(encode_data(out, Source{kSacnTestCid, long_name}, h, slots), 128U);
  const auto p = decode_data(std::span(out.data(), 128));
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->source_name.size(), 63U);
}

TEST(SacnCodec, RoundTripsSeededRandomPackets) {
  const unsigned seed = 1311;
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> slots(std::uniform_int_distribution<std::size_t>(0, 512)(rng));
    for (auto& s : slots) s = static_cast<std::uint8_t>(rng());
    DataHeader h;
    h.universe = static_cast<std::uint16_t>(std::uniform_int_distribution<int>(1, 63999)(rng));
    h.priority = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 200)(rng));
    h.sequence = static_cast<std::uint8_t>(rng());
    h.options = static_cast<std::uint8_t>(rng() & 0xE0U);
    h.sync_address = static_cast<std::uint16_t>(rng());
    h.start_code = static_cast<std::uint8_t>(rng());
    std::array<std::uint8_t, kMaxDataPacketSize> out{};
    const std::size_t n = encode_data(out, Source{kSacnTestCid, "round trip"}, h, slots);
    ASSERT_EQ(n, data_packet_size(slots.size())) << "seed " << seed;
    const auto p = decode_data(std::span(out.data(), n));
    ASSERT_TRUE(p.has_value()) << "seed " << seed;
    EXPECT_EQ(p->cid, kSacnTestCid);
    EXPECT_EQ(p->source_name, "round trip");
    EXPECT_EQ(p->header.universe, h.universe);
    EXPECT_EQ(p->header.priority, h.priority);
    EXPECT_EQ(p->header.sequence, h.sequence);
    EXPECT_EQ(p->header.options, h.options);
    EXPECT_EQ(p->header.sync_address, h.sync_address);
    EXPECT_EQ(p->header.start_code, h.start_code);
    EXPECT_EQ(std::vector<std::uint8_t>(p->slots.begin(), p->slots.end()), slots) << "seed " << seed;
  }
}

TEST(SacnCodec, RefusesEveryMalformedDataPacket) {
  const std::array<std::uint8_t, 4> slots{1, 2, 3, 4};
  std::array<std::uint8_t, 130> good{};
  ASSERT_EQ(encode_data(good, Source{kSacnTestCid, "avar"}, DataHeader{}, slots), good.size());
  ASSERT_TRUE(decode_data(good).has_value());
  for (std::size_t n = 0; n < good.size(); ++n) EXPECT_FALSE(decode_data(std::span(good.data(), n)).has_value()) << n;
  // Every byte of every fixed field, changed, is refused; the CID, name (but its NUL), priority
  // in range, sync, sequence, options, universe in range and the data may take any value.
  std::vector<std::size_t> fixed;
  for (std::size_t at = 0; at < 22; ++at) fixed.push_back(at);
  for (std::size_t at = 38; at < 44; ++at) fixed.push_back(at);
  for (std::size_t at = 115; at < 125; ++at) fixed.push_back(at);
  for (std::size_t at : fixed) {
    auto bad = good;
    bad[at] ^= 0x01;
    EXPECT_FALSE(decode_data(bad).has_value()) << "byte " << at;
  }
  auto high_priority = good;
  high_priority[108] = 201;
  EXPECT_FALSE(decode_data(high_priority).has_value());
  auto universe_zero = good;
  universe_zero[113] = 0, universe_zero[114] = 0;
  EXPECT_FALSE(decode_data(universe_zero).has_value());
  auto universe_high = good;
  universe_high[113] = 0xFA, universe_high[114] = 0x00;  // 64000
  EXPECT_FALSE(decode_data(universe_high).has_value());
  auto unterminated = good;
  std::fill(unterminated.begin() + 44, unterminated.begin() + 108, std::uint8_t{'n'});
  EXPECT_FALSE(decode_data(unterminated).has_value());
  // A discovery packet is no data packet, and the reverse.
  std::array<std::uint8_t, kMaxDiscoveryPacketSize> discovery{};
  const std::array<std::uint16_t, 1> one{1};
  const std::size_t n = encode_discovery(discovery, Source{kSacnTestCid, "avar"}, 0, 0, one);
  std::array<std::uint16_t, 4> list{};
  EXPECT_FALSE(decode_data(std::span(discovery.data(), n)).has_value());
  EXPECT_FALSE(decode_discovery(good, list).has_value());
  EXPECT_FALSE(decode_discovery(std::span(discovery.data(), n - 1), list).has_value());
}

}  // namespace
}  // namespace avar::firmware_iface::sacn
