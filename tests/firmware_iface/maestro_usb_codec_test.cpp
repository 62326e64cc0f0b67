// Golden bytes for the Maestro's native USB requests. The vectors are derived by hand from
// Pololu's USB SDK (pololu-usb-sdk: Maestro/Usc/Usc.cs for which request carries what in wValue
// and wIndex, Maestro/Usc/Usc_protocol.cs for the request codes and the packed little-endian
// layouts of ServoStatus, MicroMaestroVariables and MiniMaestroVariables): a setup packet is
// bmRequestType, bRequest, wValue lo/hi, wIndex lo/hi, wLength lo/hi.
#include "avar/firmware_iface/maestro_usb_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

namespace avar::firmware_iface::maestro_usb {
namespace {

using Setup8 = std::array<std::uint8_t, 8>;

TEST(MaestroUsbCodec, SetTargetPutsTheTargetInValueAndTheChannelInIndex) {
  // 6000 quarter-µs = 1500 µs = 0x1770; 4000 = 0x0FA0.
  EXPECT_EQ(set_target(0, 6000).bytes(), (Setup8{0x40, 0x85, 0x70, 0x17, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(set_target(5, 4000).bytes(), (Setup8{0x40, 0x85, 0xA0, 0x0F, 0x05, 0x00, 0x00, 0x00}));
  EXPECT_EQ(set_target(23, 0).bytes(), (Setup8{0x40, 0x85, 0x00, 0x00, 0x17, 0x00, 0x00, 0x00}));
}

TEST(MaestroUsbCodec, SpeedAndAccelerationShareOneRequestAndDifferByIndexBit7) {
  // Speed 140 on channel 5 (the guide's worked example, here over USB).
  EXPECT_EQ(set_speed(5, 140).bytes(), (Setup8{0x40, 0x84, 0x8C, 0x00, 0x05, 0x00, 0x00, 0x00}));
  EXPECT_EQ(set_speed(1, 10000).bytes(), (Setup8{0x40, 0x84, 0x10, 0x27, 0x01, 0x00, 0x00, 0x00}));
  // Acceleration 4 on channel 2: wIndex = 2 | 0x80.
  EXPECT_EQ(set_acceleration(2, 4).bytes(), (Setup8{0x40, 0x84, 0x04, 0x00, 0x82, 0x00, 0x00, 0x00}));
  // The device takes 0..255: larger accelerations saturate.
  EXPECT_EQ(set_acceleration(23, 300).bytes(), (Setup8{0x40, 0x84, 0xFF, 0x00, 0x97, 0x00, 0x00, 0x00}));
}

TEST(MaestroUsbCodec, ClearErrorsHasNoArguments) {
  EXPECT_EQ(clear_errors().bytes(), (Setup8{0x40, 0x86, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}));
}

TEST(MaestroUsbCodec, GetVariablesAsksForTheModelsLayout) {
  // Micro: 98 bytes of variables (1+1+2+2 + 3×2 guard + 32×2 stack + 10×2 call stack + 1+1)
  // and 6 servo records of 7 bytes = 140 = 0x8C.
  EXPECT_EQ(get_variables(6).bytes(), (Setup8{0xC0, 0x83, 0x00, 0x00, 0x00, 0x00, 0x8C, 0x00}));
  // Mini: 8 bytes (1+1+2+2+1+1), the same for 12, 18 and 24 channels.
  for (const int n : {12, 18, 24})
    EXPECT_EQ(get_variables(n).bytes(), (Setup8{0xC0, 0x83, 0x00, 0x00, 0x00, 0x00, 0x08, 0x00})) << n;
}

TEST(MaestroUsbCodec, GetServoSettingsAsksForSevenBytesAChannel) {
  EXPECT_EQ(get_servo_settings(12).bytes(), (Setup8{0xC0, 0x87, 0x00, 0x00, 0x00, 0x00, 0x54, 0x00}));  // 84
  EXPECT_EQ(get_servo_settings(18).bytes(), (Setup8{0xC0, 0x87, 0x00, 0x00, 0x00, 0x00, 0x7E, 0x00}));  // 126
  EXPECT_EQ(get_servo_settings(24).bytes(), (Setup8{0xC0, 0x87, 0x00, 0x00, 0x00, 0x00, 0xA8, 0x00}));  // 168
  // Positions: one request either way, Get Variables on the Micro, Get Servo Settings on a Mini.
  EXPECT_EQ(get_positions(6), get_variables(6));
  EXPECT_EQ(get_positions(12), get_servo_settings(12));
  EXPECT_TRUE(get_positions(6).device_to_host());
  EXPECT_FALSE(set_target(0, 0).device_to_host());
}

TEST(MaestroUsbCodec, ProductIdsAndChannelCountsMapBothWays) {
  EXPECT_EQ(kVendorId, 0x1FFB);
  EXPECT_EQ(product_id_for_channels(6), 0x0089);
  EXPECT_EQ(product_id_for_channels(12), 0x008A);
  EXPECT_EQ(product_id_for_channels(18), 0x008B);
  EXPECT_EQ(product_id_for_channels(24), 0x008C);
  EXPECT_EQ(product_id_for_channels(8), 0);
  for (const std::uint16_t id : kProductIds) EXPECT_EQ(product_id_for_channels(channels_for_product_id(id)), id);
  EXPECT_EQ(channels_for_product_id(0x0088), 0);  // the Micro Maestro's bootloader is no Maestro to drive
}

TEST(MaestroUsbCodec, DecodesTheMicroMaestroVariablesByHand) {
  // A Micro Maestro reply: serial protocol error (bit 4) latched; channel 1 outputs 1500 µs
  // toward 1750 µs at speed 140, acceleration 4; every other channel off.
  std::vector<std::uint8_t> reply(140, 0);
  reply[2] = 0x10;  // errors, low byte
  reply[3] = 0x00;
  reply[96] = 0x01;                                                             // scriptDone
  const std::uint8_t channel1[7] = {0x70, 0x17, 0x58, 0x1B, 0x8C, 0x00, 0x04};  // 6000, 7000, 140, 4
  std::copy(std::begin(channel1), std::end(channel1), reply.begin() + 98 + 7);
  std::uint16_t errors = 0;
  ASSERT_TRUE(decode_errors(reply, &errors));
  EXPECT_EQ(errors, 0x0010);
  ServoStatus s;
  ASSERT_TRUE(decode_servo_status(reply, 6, 1, &s));
  EXPECT_EQ(s, (ServoStatus{6000, 7000, 140, 4}));
  ASSERT_TRUE(decode_servo_status(reply, 6, 0, &s));
  EXPECT_EQ(s, ServoStatus{});
  // Channel 5 is the last record (bytes 133..139); channel 6 is not there.
  EXPECT_TRUE(decode_servo_status(reply, 6, 5, &s));
  EXPECT_FALSE(decode_servo_status(reply, 6, 6, &s));
}

TEST(MaestroUsbCodec, DecodesTheMiniMaestroServoSettingsByHand) {
  std::vector<std::uint8_t> reply(84, 0);
  // Channel 11, the last of a Mini 12, at offset 77: 2000 µs (8000 = 0x1F40), target the same,
  // no speed limit, acceleration 255.
  const std::uint8_t channel11[7] = {0x40, 0x1F, 0x40, 0x1F, 0x00, 0x00, 0xFF};
  std::copy(std::begin(channel11), std::end(channel11), reply.begin() + 77);
  ServoStatus s;
  ASSERT_TRUE(decode_servo_status(reply, 12, 11, &s));
  EXPECT_EQ(s, (ServoStatus{8000, 8000, 0, 255}));
  // The Mini's Get Variables reply: errors at offset 2, little-endian.
  const std::vector<std::uint8_t> variables{0, 0, 0x00, 0x01, 0, 0, 1, 0};
  std::uint16_t errors = 0;
  ASSERT_TRUE(decode_errors(variables, &errors));
  EXPECT_EQ(errors, 0x0100);  // script program counter error
}

TEST(MaestroUsbCodec, ShortRepliesAreRefusedNotReadPastTheirEnd) {
  const std::vector<std::uint8_t> short_reply(83, 0);
  ServoStatus s{1, 2, 3, 4};
  EXPECT_FALSE(decode_servo_status(short_reply, 12, 11, &s));
  EXPECT_EQ(s, (ServoStatus{1, 2, 3, 4}));  // untouched
  EXPECT_FALSE(decode_servo_status(short_reply, 12, -1, &s));
  std::uint16_t errors = 7;
  EXPECT_FALSE(decode_errors(std::span(short_reply).first(7), &errors));
  EXPECT_EQ(errors, 7);
}

TEST(MaestroUsbCodec, ServoRecordsRoundTripInBothLayouts) {
  const unsigned seed = 19;
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> word(0, 0xFFFF);
  for (const int channels : {6, 12, 18, 24}) {
    std::vector<std::uint8_t> reply(get_positions(channels).length, 0);
    const std::size_t base = channels == 6 ? kMicroVariablesSize : 0;
    std::vector<ServoStatus> written;
    for (int c = 0; c < channels; ++c) {
      const ServoStatus s{static_cast<std::uint16_t>(word(random)), static_cast<std::uint16_t>(word(random)),
                          static_cast<std::uint16_t>(word(random)), static_cast<std::uint8_t>(word(random) & 0xFF)};
      encode_servo_status(std::span(reply).subspan(base + static_cast<std::size_t>(c) * kServoRecordSize), s);
      written.push_back(s);
    }
    for (int c = 0; c < channels; ++c) {
      ServoStatus s;
      ASSERT_TRUE(decode_servo_status(reply, channels, c, &s));
      EXPECT_EQ(s, written[static_cast<std::size_t>(c)]) << "seed " << seed << ", " << channels << " channels, channel " << c;
    }
  }
}

}  // namespace
}  // namespace avar::firmware_iface::maestro_usb
