// Golden bytes from ../shared/protocols/enttec-dmx-usb-pro.md, section 6 (vectors E1..E5), and
// the resynchronising decoder.
#include "avar/firmware_iface/dmx_codec.hpp"

#include <gtest/gtest.h>

#include "../support/encode.hpp"

#include <array>
#include <random>
#include <vector>

namespace avar::firmware_iface::dmx {
namespace {

using avar::testing::Bytes;

template <class F>
Bytes encode(F&& f) {
  return avar::testing::encode_into<kMaxMessageSize>(f);
}

TEST(DmxCodec, E1_FullUniverse) {
  Bytes slots(512);
  for (std::size_t i = 0; i < slots.size(); ++i) slots[i] = static_cast<std::uint8_t>(i * 7);
  const Bytes m = encode([&](auto o) { return encode_send_dmx(o, slots); });
  ASSERT_EQ(m.size(), 518u);
  EXPECT_EQ(Bytes(m.begin(), m.begin() + 5), (Bytes{0x7E, 0x06, 0x01, 0x02, 0x00}));
  EXPECT_EQ(Bytes(m.begin() + 5, m.end() - 1), slots);
  EXPECT_EQ(m.back(), 0xE7);
}

TEST(DmxCodec, E2_E3_ShortUniversesArePaddedTo24Slots) {
  Bytes e2{0x7E, 0x06, 0x19, 0x00, 0x00};
  e2.resize(5 + 24, 0x00);
  e2.push_back(0xE7);
  EXPECT_EQ(encode([](auto o) { return encode_send_dmx(o, {}); }), e2);
  EXPECT_EQ(e2.size(), 30u);
  Bytes e3 = e2;
  e3[5] = 0xFF, e3[6] = 0x80;
  const Bytes two{0xFF, 0x80};
  EXPECT_EQ(encode([&](auto o) { return encode_send_dmx(o, two); }), e3);
  EXPECT_EQ(send_dmx_size(2), 30u);
  EXPECT_EQ(send_dmx_size(32), 38u);  // the README's 16 x 16-bit row
}

TEST(DmxCodec, E4_E5_WidgetRequests) {
  EXPECT_EQ(encode([](auto o) { return encode_get_widget_parameters(o); }), (Bytes{0x7E, 0x03, 0x02, 0x00, 0x00, 0x00, 0xE7}));
  EXPECT_EQ(encode([](auto o) { return encode_get_serial_number(o); }), (Bytes{0x7E, 0x0A, 0x00, 0x00, 0xE7}));
  const WidgetParameters p{0, 9, 1, 40};
  EXPECT_EQ(encode([&](auto o) { return encode_set_widget_parameters(o, p); }),
            (Bytes{0x7E, 0x04, 0x05, 0x00, 0x00, 0x00, 0x09, 0x01, 0x28, 0xE7}));
  EXPECT_TRUE(encode([](auto o) { return encode_set_widget_parameters(o, {0, 8, 1, 40}); }).empty());
  EXPECT_TRUE(encode([](auto o) { return encode_set_widget_parameters(o, {0, 9, 1, 41}); }).empty());
}

TEST(DmxCodec, WidgetParametersReplyRoundTrips) {
  const WidgetParameters p{0x0144, 20, 3, 30};
  const Bytes m = encode([&](auto o) { return encode_widget_parameters_reply(o, p, {}); });
  Message msg;
  std::size_t used = 0;
  ASSERT_EQ(decode_message(m, &msg, &used), DecodeResult::ok);
  EXPECT_EQ(msg.label, kGetWidgetParameters);
  WidgetParameters q;
  ASSERT_TRUE(decode_widget_parameters(msg.data, &q));
  EXPECT_EQ(q.firmware, 0x0144);
  EXPECT_EQ(q.break_time, 20);
  EXPECT_EQ(q.mab_time, 3);
  EXPECT_EQ(q.output_rate, 30);
  EXPECT_FALSE(decode_widget_parameters(std::span(msg.data).first(4), &q));
}

TEST(DmxCodec, DecoderResynchronises) {
  Message m;
  std::size_t used = 0;
  const Bytes noise{0x01, 0x02, 0x7E, 0x0A, 0x00, 0x00, 0xE7};
  ASSERT_EQ(decode_message(noise, &m, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 2u);
  ASSERT_EQ(decode_message(std::span(noise).subspan(2), &m, &used), DecodeResult::ok);
  EXPECT_EQ(m.label, kGetSerialNumber);
  const Bytes no_end{0x7E, 0x0A, 0x00, 0x00, 0x00, 0x7E, 0x0A, 0x00, 0x00, 0xE7};
  ASSERT_EQ(decode_message(no_end, &m, &used), DecodeResult::bad_framing);
  EXPECT_EQ(used, 1u);
  const Bytes too_long{0x7E, 0x06, 0x59, 0x02};  // 601
  EXPECT_EQ(decode_message(too_long, &m, &used), DecodeResult::bad_framing);
  const Bytes partial{0x7E, 0x06, 0x19, 0x00, 0x00};
  EXPECT_EQ(decode_message(partial, &m, &used), DecodeResult::need_more);
  EXPECT_EQ(used, 0u);
}

TEST(DmxCodec, RandomUniversesRoundTrip) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    Bytes slots(std::uniform_int_distribution<std::size_t>(0, 512)(rng));
    for (auto& s : slots) s = static_cast<std::uint8_t>(rng());
    const Bytes wire = encode([&](auto o) { return encode_send_dmx(o, slots); });
    ASSERT_EQ(wire.size(), send_dmx_size(slots.size()));
    Message m;
    std::size_t used = 0;
    ASSERT_EQ(decode_message(wire, &m, &used), DecodeResult::ok);
    ASSERT_EQ(m.label, kOutputOnlySendDmx);
    EXPECT_EQ(m.data[0], kDimmerStartCode);
    EXPECT_TRUE(std::equal(slots.begin(), slots.end(), m.data.begin() + 1));
  }
  EXPECT_DOUBLE_EQ(dmx_packet_seconds(512), 22676e-6);
  EXPECT_DOUBLE_EQ(dmx_packet_seconds(32), 1556e-6);
  EXPECT_DOUBLE_EQ(dmx_packet_seconds(1), 1204e-6);
}

}  // namespace
}  // namespace avar::firmware_iface::dmx
