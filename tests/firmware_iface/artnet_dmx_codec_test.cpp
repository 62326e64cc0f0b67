#include "avar/firmware_iface/artnet_dmx_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

namespace avar::firmware_iface::artnet {
namespace {

TEST(ArtDmxCodec, GoldenPacketFromTheArtNet4Layout) {
  // Sequence 7, physical 1, Net 1, Sub-Net 2, Universe 3 (Port-Address 0x0123), 4 slots.
  const std::array<std::uint8_t, 4> slots{0x00, 0x7F, 0x80, 0xFF};
  std::array<std::uint8_t, kMaxDmxPacketSize> out{};
  ASSERT_EQ(encode_dmx(out, 7, 1, port_address(1, 2, 3), slots), 22U);
  const std::vector<std::uint8_t> expected{'A',  'r',  't',  '-', 'N', 'e', 't', 0x00,  // ID
                                           0x00, 0x50,                                  // OpCode 0x5000, low byte first
                                           0x00, 0x0E,                                  // ProtVerHi, ProtVerLo 14
                                           0x07,                                        // Sequence
                                           0x01,                                        // Physical
                                           0x23,                                        // SubUni: Sub-Net 2, Universe 3
                                           0x01,                                        // Net 1
                                           0x00, 0x04,                                  // Length, high byte first
                                           0x00, 0x7F, 0x80, 0xFF};
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + 22), expected);
}

TEST(ArtDmxCodec, PadsOddLengthsToEvenAndRefusesBadArguments) {
  std::array<std::uint8_t, kMaxDmxPacketSize + 2> out{};
  out.fill(0xAA);
  const std::array<std::uint8_t, 3> three{1, 2, 3};
  ASSERT_EQ(encode_dmx(out, 0, 0, 0, three), dmx_packet_size(3));
  EXPECT_EQ(dmx_packet_size(3), 22U);
  EXPECT_EQ(out[16], 0x00);
  EXPECT_EQ(out[17], 0x04);
  EXPECT_EQ(out[21], 0x00);  // the pad slot
  const std::array<std::uint8_t, 1> one{9};
  EXPECT_EQ(encode_dmx(out, 0, 0, 0, one), 20U);
  const std::vector<std::uint8_t> too_many(513, 0);
  EXPECT_EQ(encode_dmx(out, 0, 0, 0, too_many), 0U);
  EXPECT_EQ(encode_dmx(out, 0, 0, 0, std::span<const std::uint8_t>{}), 0U);
  EXPECT_EQ(encode_dmx(out, 0, 0, 0x8000, three), 0U);
  std::array<std::uint8_t, 21> small{};
  EXPECT_EQ(encode_dmx(small, 0, 0, 0, three), 0U);
}

TEST(ArtDmxCodec, RoundTripsSeededRandomUniverses) {
  const unsigned seed = 20261203;
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> slots(std::uniform_int_distribution<std::size_t>(1, 256)(rng) * 2);
    for (auto& s : slots) s = static_cast<std::uint8_t>(rng());
    const auto sequence = static_cast<std::uint8_t>(rng());
    const auto address = static_cast<std::uint16_t>(rng() & 0x7FFFU);
    std::array<std::uint8_t, kMaxDmxPacketSize> out{};
    const std::size_t n = encode_dmx(out, sequence, 2, address, slots);
    ASSERT_EQ(n, kDmxHeaderSize + slots.size()) << "seed " << seed;
    const auto p = decode_dmx(std::span(out.data(), n));
    ASSERT_TRUE(p.has_value()) << "seed " << seed;
    EXPECT_EQ(p->sequence, sequence);
    EXPECT_EQ(p->physical, 2);
    EXPECT_EQ(p->port_address, address);
    EXPECT_EQ(std::vector<std::uint8_t>(p->slots.begin(), p->slots.end()), slots) << "seed " << seed;
  }
}

TEST(ArtDmxCodec, RefusesEveryMalformedPacket) {
  const std::array<std::uint8_t, 4> slots{1, 2, 3, 4};
  std::array<std::uint8_t, 22> good{};
  ASSERT_EQ(encode_dmx(good, 1, 0, 5, slots), good.size());
  ASSERT_TRUE(decode_dmx(good).has_value());
  // Every truncation, and one byte too many.
  for (std::size_t n = 0; n < good.size(); ++n) EXPECT_FALSE(decode_dmx(std::span(good.data(), n)).has_value()) << n;
  std::vector<std::uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  EXPECT_FALSE(decode_dmx(longer).has_value());
  const auto corrupted = [&](std::size_t at, std::uint8_t value) {
    auto bad = good;
    bad[at] = value;
    return decode_dmx(bad).has_value();
  };
  for (std::size_t at = 0; at < 8; ++at) EXPECT_FALSE(corrupted(at, 0x55)) << "ID byte " << at;
  EXPECT_FALSE(corrupted(9, 0x20));   // ArtPoll's OpCode
  EXPECT_FALSE(corrupted(11, 13));    // protocol version 13
  EXPECT_FALSE(corrupted(15, 0x80));  // Net bit 7
  EXPECT_FALSE(corrupted(17, 0x03));  // odd length
  EXPECT_FALSE(corrupted(17, 0x06));  // length beyond the datagram
  EXPECT_FALSE(corrupted(17, 0x00));  // length 0
  EXPECT_FALSE(corrupted(16, 0x02));  // length above 512
  EXPECT_TRUE(corrupted(12, 0x00));   // sequence 0 is allowed (sequencing off)
}

}  // namespace
}  // namespace avar::firmware_iface::artnet
