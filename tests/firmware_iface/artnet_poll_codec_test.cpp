#include "avar/firmware_iface/artnet_poll_codec.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace avar::firmware_iface::artnet {
namespace {

TEST(ArtPollCodec, GoldenArtNet4Poll) {
  Poll poll;
  poll.flags = kPollReplyOnChange | kPollTargeted;
  poll.diag_priority = 0x40;
  poll.target_top = 0x0123;
  poll.target_bottom = 0x0010;
  poll.esta_manufacturer = 0x7FF0;
  poll.oem = 0x00FF;
  std::array<std::uint8_t, kPollSize> out{};
  ASSERT_EQ(encode_poll(out, poll), 22U);
  const std::array<std::uint8_t, 22> expected{'A',  'r',  't', '-', 'N', 'e', 't', 0x00,  // ID
                                              0x00, 0x20,                                 // OpCode 0x2000
                                              0x00, 0x0E,                                 // version 14
                                              0x22,                                       // Flags
                                              0x40,                                       // DiagPriority DpMed
                                              0x01, 0x23,                                 // TargetPortAddressTop
                                              0x00, 0x10,                                 // TargetPortAddressBottom
                                              0x7F, 0xF0,                                 // EstaMan
                                              0x00, 0xFF};                                // Oem
  EXPECT_EQ(out, expected);
  const auto back = decode_poll(out);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->flags, 0x22);
  EXPECT_EQ(back->target_top, 0x0123);
  EXPECT_EQ(back->oem, 0x00FF);
}

TEST(ArtPollCodec, AcceptsArtNet3PollsAndRefusesMalformedOnes) {
  std::array<std::uint8_t, kPollSize> out{};
  ASSERT_EQ(encode_poll(out, Poll{}), kPollSize);
  const auto short_poll = decode_poll(std::span(out.data(), kMinPollSize));
  ASSERT_TRUE(short_poll.has_value());
  EXPECT_EQ(short_poll->target_top, 0x7FFF);  // every Port-Address
  for (std::size_t n = 0; n < kMinPollSize; ++n) EXPECT_FALSE(decode_poll(std::span(out.data(), n)).has_value()) << n;
  auto old = out;
  old[11] = 13;
  EXPECT_FALSE(decode_poll(old).has_value());
  auto other = out;
  other[9] = 0x50;
  EXPECT_FALSE(decode_poll(other).has_value());
}

TEST(ArtPollCodec, GoldenPollReplyFieldOffsets) {
  PollReply r;
  r.ip = {127, 0, 0, 1};
  r.version_info = 0x0102;
  r.net_switch = 0x01;
  r.sub_switch = 0x02;
  r.oem = 0x1234;
  r.status1 = 0xD0;
  r.esta_manufacturer = 0x4156;  // 'A' 'V', low byte first
  r.short_name.set("avar");
  r.long_name.set("avar animatronics controller");
  r.node_report.set("#0001 [0000] ok");
  r.num_ports = 1;
  r.port_types = {0x80, 0, 0, 0};
  r.good_output_a = {0x80, 0, 0, 0};
  r.sw_out = {0x03, 0, 0, 0};
  r.style = 1;
  r.mac = {0x02, 0x00, 0x00, 0x00, 0x00, 0x01};
  r.bind_ip = {127, 0, 0, 1};
  r.bind_index = 1;
  r.status2 = 0x08;
  std::array<std::uint8_t, kPollReplySize> out{};
  ASSERT_EQ(encode_poll_reply(out, r), 239U);
  std::array<std::uint8_t, kPollReplySize> expected{};
  const std::array<std::uint8_t, 26> head{'A',  'r',  't',  '-',  'N',  'e',  't',  0,    0x00, 0x21,  // no version follows
                                          127,  0,    0,    1,                                         // IP
                                          0x36, 0x19,                                      // port 6454, low byte first
                                          0x01, 0x02, 0x01, 0x02, 0x12, 0x34, 0x00, 0xD0,  // VersInfo .. Status1
                                          0x56, 0x41};                                     // EstaManLo, EstaManHi
  std::copy(head.begin(), head.end(), expected.begin());
  const auto text = [&](std::size_t at, std::string_view s) {
    std::copy(s.begin(), s.end(), expected.begin() + static_cast<long>(at));
  };
  text(26, "avar");
  text(44, "avar animatronics controller");
  text(108, "#0001 [0000] ok");
  expected[172] = 0x00;
  expected[173] = 0x01;  // NumPorts
  expected[174] = 0x80;  // PortTypes[0]: output, DMX512
  expected[182] = 0x80;  // GoodOutputA[0]
  expected[190] = 0x03;  // SwOut[0]
  expected[200] = 0x01;  // Style StController
  expected[201] = 0x02;
  expected[206] = 0x01;  // MAC
  expected[207] = 127;
  expected[210] = 1;     // BindIp
  expected[211] = 1;     // BindIndex
  expected[212] = 0x08;  // Status2
  EXPECT_EQ(out, expected);

  const auto back = decode_poll_reply(out);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->ip, r.ip);
  EXPECT_EQ(back->port, 6454);
  EXPECT_EQ(back->esta_manufacturer, 0x4156);
  EXPECT_EQ(back->short_name.view(), "avar");
  EXPECT_EQ(back->long_name.view(), "avar animatronics controller");
  EXPECT_EQ(back->output_port_address(0), 0x0123);
  EXPECT_EQ(back->mac, r.mac);
  EXPECT_EQ(back->status2, 0x08);
}

TEST(ArtPollCodec, PollReplyNamesAreCutAndTerminated) {
  PollReply r;
  r.short_name.set("a name far longer than eighteen");
  EXPECT_EQ(r.short_name.view(), "a name far longer");  // 17 characters and the NUL
  std::array<std::uint8_t, kPollReplySize> out{};
  ASSERT_EQ(encode_poll_reply(out, r), kPollReplySize);
  EXPECT_EQ(out[26 + 17], 0);
  r.num_ports = 5;
  EXPECT_EQ(encode_poll_reply(out, r), 0U);
}

// Found by fuzz/artnet_poll_fuzz.cpp: a reply whose name fields lack their NUL decoded to names of
// N characters, one more than NameField holds and than the encoder sends back.
TEST(ArtPollCodec, PollReplyNamesWithoutTheirNulAreCutOnDecode) {
  PollReply r;
  std::array<std::uint8_t, kPollReplySize> bytes{};
  ASSERT_EQ(encode_poll_reply(bytes, r), kPollReplySize);
  std::fill(bytes.begin() + 26, bytes.begin() + 172, std::uint8_t{'n'});  // ShortName, LongName, NodeReport
  const auto back = decode_poll_reply(bytes);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->short_name.view(), std::string(kShortNameSize - 1, 'n'));
  EXPECT_EQ(back->long_name.view(), std::string(kLongNameSize - 1, 'n'));
  EXPECT_EQ(back->node_report.view(), std::string(kNodeReportSize - 1, 'n'));
  std::array<std::uint8_t, kPollReplySize> again{};
  ASSERT_EQ(encode_poll_reply(again, *back), kPollReplySize);
  EXPECT_EQ(decode_poll_reply(again)->short_name.view(), back->short_name.view());
}

TEST(ArtPollCodec, PollReplyDecoderAcceptsShortOldRepliesAndRefusesMalformedOnes) {
  PollReply r;
  r.num_ports = 2;
  r.status2 = 0x08;
  std::array<std::uint8_t, kPollReplySize> out{};
  ASSERT_EQ(encode_poll_reply(out, r), kPollReplySize);
  const auto old = decode_poll_reply(std::span(out.data(), kMinPollReplySize));
  ASSERT_TRUE(old.has_value());
  EXPECT_EQ(old->num_ports, 2);
  EXPECT_EQ(old->status2, 0);  // beyond an old reply: zero
  EXPECT_FALSE(decode_poll_reply(std::span(out.data(), kMinPollReplySize - 1)).has_value());
  auto many = out;
  many[173] = 5;
  EXPECT_FALSE(decode_poll_reply(many).has_value());
  auto other = out;
  other[9] = 0x20;
  EXPECT_FALSE(decode_poll_reply(other).has_value());
}

}  // namespace
}  // namespace avar::firmware_iface::artnet
