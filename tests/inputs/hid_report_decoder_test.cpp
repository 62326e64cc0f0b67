// ReportDecoder: hand-built input reports of a DualShock 4 and a Logitech F310 (their real
// descriptors from tests/data/hid) become named, normalised controls; only changes are posted;
// decoding allocates nothing.
#include "avar/inputs/hid_report_decoder.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "../support/allocation_count.hpp"
#include "../support/hid_fixtures.hpp"

namespace avar::inputs::hid {
namespace {

using Bytes = std::vector<std::uint8_t>;
using testing::RecordingControlSink;

ReportDecoder hid_dec_make(const std::string& fixture) {
  return ReportDecoder(parse_report_descriptor(testing::load_hid_fixture(fixture)));
}

/// A DualShock 4 USB input report (id 1, 64 bytes): sticks, hat, 14 button bits, triggers.
Bytes hid_dec_ds4(std::array<std::uint8_t, 4> sticks, std::uint8_t hat, std::uint16_t buttons, std::uint8_t l2 = 0,
                  std::uint8_t r2 = 0) {
  Bytes r(64, 0);
  r[0] = 0x01;
  for (int i = 0; i < 4; ++i) r[1 + i] = sticks[i];
  r[5] = static_cast<std::uint8_t>((hat & 0x0F) | ((buttons & 0x0F) << 4));
  r[6] = static_cast<std::uint8_t>(buttons >> 4);
  r[7] = static_cast<std::uint8_t>((buttons >> 12) & 0x03);
  r[8] = l2;
  r[9] = r2;
  return r;
}

/// A Logitech F310 (DirectInput) input report: 8 bytes, no report id.
Bytes hid_dec_f310(std::array<std::uint8_t, 4> sticks, std::uint8_t hat, std::uint16_t buttons) {
  Bytes r(8, 0);
  for (int i = 0; i < 4; ++i) r[i] = sticks[i];
  r[4] = static_cast<std::uint8_t>((hat & 0x0F) | ((buttons & 0x0F) << 4));
  r[5] = static_cast<std::uint8_t>(buttons >> 4);
  return r;
}

constexpr std::array<std::uint8_t, 4> kCentred{0x80, 0x80, 0x80, 0x80};

struct HatPosition {
  std::uint8_t value;
  double x;
  double y;
};
// 8 positions clockwise from up; up is hat_y = -1. 8 and 15: the null state (centred).
const std::vector<HatPosition> kHidDecHat{{0, 0, -1}, {1, 1, -1}, {2, 1, 0},   {3, 1, 1}, {4, 0, 1},
                                          {5, -1, 1}, {6, -1, 0}, {7, -1, -1}, {8, 0, 0}, {15, 0, 0}};

TEST(HidReportDecoder, DualShock4ControlNames) {
  const ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  std::vector<std::string> expected{"x", "y", "z", "rz", "hat_x", "hat_y"};
  for (int b = 1; b <= 14; ++b) expected.push_back("button" + std::to_string(b));
  expected.push_back("usage_FF00_0020");
  expected.push_back("rx");
  expected.push_back("ry");
  expected.push_back("usage_FF00_0021");
  for (int n = 2; n <= 54; ++n) expected.push_back("usage_FF00_0021_" + std::to_string(n));
  ASSERT_EQ(d.controls().size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(d.controls()[i].name, expected[i]) << i;
  EXPECT_TRUE(d.controls()[0].bipolar);   // x
  EXPECT_TRUE(d.controls()[4].bipolar);   // hat_x
  EXPECT_FALSE(d.controls()[6].bipolar);  // button1
  EXPECT_TRUE(d.controls()[21].bipolar);  // rx: Rx is an axis, bipolar by the usage table
  EXPECT_EQ(d.max_report_bytes(), 64u);
}

TEST(HidReportDecoder, DualShock4SticksCentredAndFullyDeflected) {
  ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  RecordingControlSink sink;
  ASSERT_TRUE(d.decode(hid_dec_ds4(kCentred, 8, 0), sink, 42));
  for (const char* axis : {"x", "y", "z", "rz", "hat_x", "hat_y"}) EXPECT_EQ(sink.value(axis), 0.0) << axis;
  EXPECT_EQ(sink.value("button1"), 0.0);
  EXPECT_EQ(sink.value("rx"), -1.0);  // trigger released: the low end of 0..255
  EXPECT_EQ(sink.posts().front().arrived_ns, 42);
  EXPECT_EQ(sink.size(), d.controls().size());  // the first report posts everything

  ASSERT_TRUE(d.decode(hid_dec_ds4({0x00, 0xFF, 0x00, 0xFF}, 8, 0, 0xFF, 0x80), sink, 43));
  EXPECT_EQ(sink.value("x"), -1.0);
  EXPECT_EQ(sink.value("y"), 1.0);
  EXPECT_EQ(sink.value("z"), -1.0);
  EXPECT_EQ(sink.value("rz"), 1.0);
  EXPECT_EQ(sink.value("rx"), 1.0);
  EXPECT_EQ(sink.value("ry"), 0.0);
  ASSERT_TRUE(d.decode(hid_dec_ds4({0x40, 0xC0, 0x80, 0x80}, 8, 0), sink, 44));
  EXPECT_DOUBLE_EQ(sink.value("x"), -0.5);
  EXPECT_DOUBLE_EQ(sink.value("y"), 64.0 / 127.0);
}

TEST(HidReportDecoder, DualShock4EachButton) {
  ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  RecordingControlSink sink;
  d.decode(hid_dec_ds4(kCentred, 8, 0), sink, 0);
  for (int b = 1; b <= 14; ++b) {
    sink.clear();
    ASSERT_TRUE(d.decode(hid_dec_ds4(kCentred, 8, static_cast<std::uint16_t>(1u << (b - 1))), sink, 0));
    for (int other = 1; other <= 14; ++other)
      EXPECT_EQ(sink.value("button" + std::to_string(other)), other == b ? 1.0 : 0.0) << "pressed " << b;
    // Pressing one button after another: it goes to 1, the previous one back to 0.
    EXPECT_EQ(sink.size(), b == 1 ? 1u : 2u);
  }
}

TEST(HidReportDecoder, DualShock4HatPositions) {
  ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  RecordingControlSink sink;
  for (const HatPosition& p : kHidDecHat) {
    ASSERT_TRUE(d.decode(hid_dec_ds4(kCentred, p.value, 0), sink, 0));
    EXPECT_EQ(sink.value("hat_x"), p.x) << "hat " << int(p.value);
    EXPECT_EQ(sink.value("hat_y"), p.y) << "hat " << int(p.value);
  }
}

TEST(HidReportDecoder, OnlyChangedValuesArePosted) {
  ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  RecordingControlSink sink;
  const Bytes report = hid_dec_ds4(kCentred, 8, 0);
  d.decode(report, sink, 0);
  sink.clear();
  EXPECT_TRUE(d.decode(report, sink, 1));
  EXPECT_EQ(sink.size(), 0u);
  Bytes moved = report;
  moved[3] = 0xFF;  // z
  EXPECT_TRUE(d.decode(moved, sink, 2));
  ASSERT_EQ(sink.size(), 1u);
  EXPECT_EQ(sink.posts()[0].name, "z");
  EXPECT_EQ(sink.posts()[0].value, 1.0);
  EXPECT_TRUE(sink.posts()[0].bipolar);
  d.reset();
  sink.clear();
  d.decode(moved, sink, 3);
  EXPECT_EQ(sink.size(), d.controls().size());
}

TEST(HidReportDecoder, UnknownIdsAndEmptyReportsAreRefused) {
  ReportDecoder d = hid_dec_make("dualshock4_v2_usb.hex");
  RecordingControlSink sink;
  Bytes other = hid_dec_ds4(kCentred, 8, 0);
  other[0] = 0x11;  // the Bluetooth report id: not in the USB descriptor
  EXPECT_FALSE(d.decode(other, sink, 0));
  EXPECT_FALSE(d.decode(Bytes{}, sink, 0));
  EXPECT_EQ(sink.size(), 0u);
  // A short report: the fields it holds are decoded, the rest left alone.
  EXPECT_TRUE(d.decode(Bytes{0x01, 0xFF, 0x00}, sink, 0));
  EXPECT_EQ(sink.size(), 2u);
  EXPECT_EQ(sink.value("x"), 1.0);
  EXPECT_EQ(sink.value("y"), -1.0);
}

TEST(HidReportDecoder, LogitechF310Controls) {
  ReportDecoder d = hid_dec_make("logitech_f310_dinput.hex");
  ASSERT_EQ(d.controls().size(), 4u + 2 + 12 + 16);
  EXPECT_EQ(d.controls()[3].name, "rz");
  EXPECT_EQ(d.controls()[17].name, "button12");
  EXPECT_EQ(d.controls()[18].name, "usage_FF00_0001");
  EXPECT_EQ(d.controls()[19].name, "usage_FF00_0001_2");
  RecordingControlSink sink;
  ASSERT_TRUE(d.decode(hid_dec_f310(kCentred, 8, 0), sink, 0));
  for (const char* axis : {"x", "y", "z", "rz", "hat_x", "hat_y"}) EXPECT_EQ(sink.value(axis), 0.0) << axis;
  ASSERT_TRUE(d.decode(hid_dec_f310({0xFF, 0x00, 0xFF, 0x00}, 8, 0), sink, 0));
  EXPECT_EQ(sink.value("x"), 1.0);
  EXPECT_EQ(sink.value("y"), -1.0);
  EXPECT_EQ(sink.value("z"), 1.0);
  EXPECT_EQ(sink.value("rz"), -1.0);
  for (int b = 1; b <= 12; ++b) {
    ASSERT_TRUE(d.decode(hid_dec_f310(kCentred, 8, static_cast<std::uint16_t>(1u << (b - 1))), sink, 0));
    for (int other = 1; other <= 12; ++other)
      EXPECT_EQ(sink.value("button" + std::to_string(other)), other == b ? 1.0 : 0.0) << "pressed " << b;
  }
  for (const HatPosition& p : kHidDecHat) {
    ASSERT_TRUE(d.decode(hid_dec_f310(kCentred, p.value, 0), sink, 0));
    EXPECT_EQ(sink.value("hat_x"), p.x) << "hat " << int(p.value);
    EXPECT_EQ(sink.value("hat_y"), p.y) << "hat " << int(p.value);
  }
}

TEST(HidReportDecoder, SignedAxesCentreOnZero) {
  // X: -127..127 in 8 bits; Y: -32768..32767 in 16 bits; Slider 0..1023 in 16 bits.
  const Bytes desc{0x05, 0x01, 0x09, 0x30, 0x15, 0x81, 0x25, 0x7F, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0x09, 0x31, 0x16, 0x00,
                   0x80, 0x26, 0xFF, 0x7F, 0x75, 0x10, 0x81, 0x02, 0x09, 0x36, 0x15, 0x00, 0x26, 0xFF, 0x03, 0x81, 0x02};
  ReportDecoder d(parse_report_descriptor(desc));
  RecordingControlSink sink;
  d.decode(Bytes{0x00, 0x00, 0x00, 0x00, 0x00}, sink, 0);
  EXPECT_EQ(sink.value("x"), 0.0);
  EXPECT_EQ(sink.value("y"), 0.0);
  EXPECT_EQ(sink.value("slider"), 0.0);
  EXPECT_FALSE(sink.posts()[2].bipolar);
  d.decode(Bytes{0x81, 0x00, 0x80, 0xFF, 0x03}, sink, 0);  // -127, -32768, 1023
  EXPECT_EQ(sink.value("x"), -1.0);
  EXPECT_EQ(sink.value("y"), -1.0);
  EXPECT_EQ(sink.value("slider"), 1.0);
  d.decode(Bytes{0x7F, 0xFF, 0x7F, 0x00, 0x02}, sink, 0);  // 127, 32767, 512
  EXPECT_EQ(sink.value("x"), 1.0);
  EXPECT_EQ(sink.value("y"), 1.0);
  EXPECT_DOUBLE_EQ(sink.value("slider"), 512.0 / 1023.0);
  d.decode(Bytes{0x80, 0xFF, 0x7F, 0x00, 0x02}, sink, 0);  // -128: outside the extent, clamped
  EXPECT_EQ(sink.value("x"), -1.0);
}

TEST(HidReportDecoder, DuplicateUsagesAreNumbered) {
  // Two X, two Y (a two-stick joystick written with repeated usages), a dial and a wheel.
  const Bytes desc{0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x09, 0x30, 0x09, 0x31, 0x09, 0x37,
                   0x09, 0x38, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x06, 0x81, 0x02};
  const ReportDecoder d(parse_report_descriptor(desc));
  const std::vector<std::string> expected{"x", "y", "x2", "y2", "dial", "wheel"};
  ASSERT_EQ(d.controls().size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(d.controls()[i].name, expected[i]);
  EXPECT_FALSE(d.controls()[5].bipolar);
}

TEST(HidReportDecoder, ArrayFieldsPressTheUsagesTheyList) {
  // Two slots naming buttons 1..8 (0: none), as keyboards report keys.
  const Bytes desc{0x05, 0x09, 0x19, 0x00, 0x29, 0x08, 0x15, 0x00, 0x25, 0x08, 0x75, 0x08, 0x95, 0x02, 0x81, 0x00};
  ReportDecoder d(parse_report_descriptor(desc));
  ASSERT_EQ(d.controls().size(), 8u);  // usage id 0 ("no button") names no control
  EXPECT_EQ(d.controls()[0].name, "button1");
  RecordingControlSink sink;
  d.decode(Bytes{3, 5}, sink, 0);
  for (int b = 1; b <= 8; ++b) EXPECT_EQ(sink.value("button" + std::to_string(b)), (b == 3 || b == 5) ? 1.0 : 0.0);
  sink.clear();
  d.decode(Bytes{5, 0}, sink, 0);
  ASSERT_EQ(sink.size(), 1u);
  EXPECT_EQ(sink.posts()[0].name, "button3");
  EXPECT_EQ(sink.posts()[0].value, 0.0);
}

TEST(HidReportDecoder, UsageNamesFollowTheTables) {
  EXPECT_EQ(usage_control_name(make_usage(0x01, 0x30)), "x");
  EXPECT_EQ(usage_control_name(make_usage(0x01, 0x35)), "rz");
  EXPECT_EQ(usage_control_name(make_usage(0x01, 0x36)), "slider");
  EXPECT_EQ(usage_control_name(make_usage(0x01, 0x39)), "hat");
  EXPECT_EQ(usage_control_name(make_usage(0x09, 17)), "button17");
  EXPECT_EQ(usage_control_name(make_usage(0x02, 0xC5)), "usage_0002_00C5");  // Simulation: Brake
  EXPECT_EQ(usage_control_name(make_usage(0x01, 0x40)), "usage_0001_0040");  // Vx
}

class HidDecCountingSink final : public ControlSink {
 public:
  void post(std::string_view, double value, bool, std::int64_t) noexcept override {
    ++posts;
    sum += value;
  }
  long posts = 0;
  double sum = 0.0;
};

TEST(HidReportDecoder, DecodingAllocatesNothing) {
  ReportDecoder ds4 = hid_dec_make("dualshock4_v2_usb.hex");
  ReportDecoder f310 = hid_dec_make("logitech_f310_dinput.hex");
  std::vector<Bytes> reports;
  for (int i = 0; i < 64; ++i) {
    const auto v = static_cast<std::uint8_t>(i * 4);
    reports.push_back(hid_dec_ds4({v, static_cast<std::uint8_t>(255 - v), v, v}, static_cast<std::uint8_t>(i % 9),
                                  static_cast<std::uint16_t>(i * 257), v, v));
  }
  const Bytes pad = hid_dec_f310({1, 2, 3, 4}, 3, 0x0FFF);
  HidDecCountingSink sink;
  const long before = testing::allocations.load();
  for (int round = 0; round < 100; ++round) {
    for (const Bytes& r : reports) ds4.decode(r, sink, round);
    f310.decode(pad, sink, round);
  }
  EXPECT_EQ(testing::allocations.load() - before, 0);
  EXPECT_GT(sink.posts, 0);
}

}  // namespace
}  // namespace avar::inputs::hid
