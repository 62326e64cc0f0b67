#include "avar/firmware_iface/artnet_header.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace avar::firmware_iface::artnet {
namespace {

TEST(ArtNetHeader, WritesIdLittleEndianOpCodeAndBigEndianVersion) {
  std::array<std::uint8_t, 12> out{};
  ASSERT_EQ(write_header(OpCode::dmx, true, out), 12U);
  const std::array<std::uint8_t, 12> expected{'A', 'r', 't', '-', 'N', 'e', 't', 0, 0x00, 0x50, 0x00, 0x0E};
  EXPECT_EQ(out, expected);
  std::array<std::uint8_t, 10> unversioned{};
  EXPECT_EQ(write_header(OpCode::poll_reply, false, unversioned), 10U);
  EXPECT_EQ(unversioned[8], 0x00);
  EXPECT_EQ(unversioned[9], 0x21);
  std::array<std::uint8_t, 11> small{};
  EXPECT_EQ(write_header(OpCode::dmx, true, small), 0U);
}

TEST(ArtNetHeader, ReadsTheOpCodeOfArtNetDatagramsOnly) {
  std::vector<std::uint8_t> packet{'A', 'r', 't', '-', 'N', 'e', 't', 0, 0x00, 0x97, 0x00, 0x0E};
  EXPECT_EQ(read_opcode(packet), 0x9700);
  EXPECT_TRUE(supported_version(packet));
  packet[11] = 13;
  EXPECT_FALSE(supported_version(packet));
  packet[3] = '_';
  EXPECT_FALSE(read_opcode(packet));
  EXPECT_FALSE(read_opcode(std::span<const std::uint8_t>(packet).first(9)));
}

}  // namespace
}  // namespace avar::firmware_iface::artnet
