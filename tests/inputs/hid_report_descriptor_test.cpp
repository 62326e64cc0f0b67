// parse_report_descriptor: the layouts of two real pads' descriptors (tests/data/hid), the HID 1.11
// item rules one at a time, and malformed descriptors refused with the offending byte offset.
#include "avar/inputs/hid_report_descriptor.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "../support/hid_fixtures.hpp"

namespace avar::inputs::hid {
namespace {

using Bytes = std::vector<std::uint8_t>;

const InputField* hid_desc_find(const ReportDescriptor& d, Usage usage, std::size_t nth = 0) {
  for (const InputField& f : d.fields)
    if (!f.array && f.usage == usage && nth-- == 0) return &f;
  return nullptr;
}

/// The error parse_report_descriptor throws for `bytes` (fails the test when it does not throw).
HidDescriptorError hid_desc_error(const Bytes& bytes) {
  try {
    parse_report_descriptor(bytes);
  } catch (const HidDescriptorError& e) {
    return e;
  }
  ADD_FAILURE() << "the descriptor was accepted";
  return HidDescriptorError(0, "");
}

TEST(HidReportDescriptor, DualShock4InputReportLayout) {
  const ReportDescriptor d = parse_report_descriptor(testing::load_hid_fixture("dualshock4_v2_usb.hex"));
  EXPECT_TRUE(d.numbered);
  EXPECT_EQ(d.application, make_usage(kGenericDesktopPage, 0x05));  // Game Pad
  ASSERT_EQ(d.reports.size(), 1u);                                  // report 5 is an output, the rest features
  EXPECT_EQ(d.reports[0].report_id, 1);
  EXPECT_EQ(d.reports[0].bits, 63u * 8);
  EXPECT_EQ(d.max_report_bytes(), 64u);
  // 4 stick bytes, the hat, 14 buttons, a 6-bit counter, 2 triggers, 54 vendor bytes.
  ASSERT_EQ(d.fields.size(), 4u + 1 + 14 + 1 + 2 + 54);
  const std::uint16_t axes[] = {0x30, 0x31, 0x32, 0x35};
  for (int i = 0; i < 4; ++i) {
    const InputField* f = hid_desc_find(d, make_usage(kGenericDesktopPage, axes[i]));
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->report_id, 1);
    EXPECT_EQ(f->bit_offset, 8u * i);
    EXPECT_EQ(f->bit_size, 8u);
    EXPECT_EQ(f->logical_minimum, 0);
    EXPECT_EQ(f->logical_maximum, 255);
  }
  const InputField* hat = hid_desc_find(d, make_usage(kGenericDesktopPage, kHatSwitch));
  ASSERT_NE(hat, nullptr);
  EXPECT_EQ(hat->bit_offset, 32u);
  EXPECT_EQ(hat->bit_size, 4u);
  EXPECT_TRUE(hat->null_state);
  EXPECT_EQ(hat->logical_maximum, 7);
  EXPECT_EQ(hat->physical_maximum, 315);
  for (std::uint16_t b = 1; b <= 14; ++b) {
    const InputField* f = hid_desc_find(d, make_usage(kButtonPage, b));
    ASSERT_NE(f, nullptr) << "button " << b;
    EXPECT_EQ(f->bit_offset, 35u + b);
    EXPECT_EQ(f->bit_size, 1u);
  }
  const InputField* counter = hid_desc_find(d, make_usage(0xFF00, 0x20));
  ASSERT_NE(counter, nullptr);
  EXPECT_EQ(counter->bit_offset, 50u);
  EXPECT_EQ(counter->bit_size, 6u);
  EXPECT_EQ(hid_desc_find(d, make_usage(kGenericDesktopPage, 0x33))->bit_offset, 56u);  // Rx: L2
  EXPECT_EQ(hid_desc_find(d, make_usage(kGenericDesktopPage, 0x34))->bit_offset, 64u);  // Ry: R2
  // One usage for 54 bytes: the last usage repeats.
  const InputField* last = hid_desc_find(d, make_usage(0xFF00, 0x21), 53);
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->bit_offset, 72u + 53 * 8);
  EXPECT_EQ(hid_desc_find(d, make_usage(0xFF00, 0x21), 54), nullptr);
}

TEST(HidReportDescriptor, LogitechF310InputReportLayout) {
  const ReportDescriptor d = parse_report_descriptor(testing::load_hid_fixture("logitech_f310_dinput.hex"));
  EXPECT_FALSE(d.numbered);
  EXPECT_EQ(d.application, make_usage(kGenericDesktopPage, 0x04));  // Joystick
  ASSERT_EQ(d.reports.size(), 1u);
  EXPECT_EQ(d.reports[0].report_id, 0);
  EXPECT_EQ(d.reports[0].bits, 64u);
  EXPECT_EQ(d.max_report_bytes(), 8u);
  ASSERT_EQ(d.fields.size(), 4u + 1 + 12 + 16);
  EXPECT_EQ(hid_desc_find(d, make_usage(kGenericDesktopPage, 0x35))->bit_offset, 24u);
  const InputField* hat = hid_desc_find(d, make_usage(kGenericDesktopPage, kHatSwitch));
  ASSERT_NE(hat, nullptr);
  EXPECT_EQ(hat->bit_offset, 32u);
  EXPECT_EQ(hat->logical_minimum, 0);
  EXPECT_EQ(hat->logical_maximum, 7);
  EXPECT_TRUE(hat->null_state);
  EXPECT_EQ(hid_desc_find(d, make_usage(kButtonPage, 1))->bit_offset, 36u);
  EXPECT_EQ(hid_desc_find(d, make_usage(kButtonPage, 12))->bit_offset, 47u);
  // Buttons inherit Physical Maximum 1 set for them, the sticks 0..255.
  EXPECT_EQ(hid_desc_find(d, make_usage(kButtonPage, 12))->physical_maximum, 1);
  EXPECT_EQ(hid_desc_find(d, make_usage(0xFF00, 0x01), 15)->bit_offset, 63u);
}

TEST(HidReportDescriptor, ExtentsAreSignExtendedByTheirItemSize) {
  const Bytes d{0x05, 0x01, 0x09, 0x30,              // X:
                0x15, 0x81, 0x25, 0x7F,              // -127..127 (one byte)
                0x75, 0x08, 0x95, 0x01, 0x81, 0x02,  //
                0x09, 0x31,                          // Y:
                0x16, 0x00, 0x80, 0x26, 0xFF, 0x7F,  // -32768..32767 (two bytes)
                0x75, 0x10, 0x81, 0x02,              //
                0x09, 0x32,                          // Z:
                0x15, 0x00, 0x25, 0xFF,              // 0..255 written without its sign byte
                0x75, 0x08, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 3u);
  EXPECT_EQ(r.fields[0].logical_minimum, -127);
  EXPECT_EQ(r.fields[0].logical_maximum, 127);
  EXPECT_TRUE(r.fields[0].is_signed());
  EXPECT_EQ(r.fields[1].logical_minimum, -32768);
  EXPECT_EQ(r.fields[1].logical_maximum, 32767);
  EXPECT_EQ(r.fields[1].bit_offset, 8u);
  EXPECT_EQ(r.fields[2].logical_minimum, 0);
  EXPECT_EQ(r.fields[2].logical_maximum, 255);
  EXPECT_FALSE(r.fields[2].is_signed());
  EXPECT_EQ(r.reports[0].bits, 32u);
}

TEST(HidReportDescriptor, ExtendedUsagesKeepTheirOwnPage) {
  // Usage page Generic Desktop, but a 4-byte usage naming Button 3 and another naming X.
  const Bytes d{0x05, 0x01, 0x0B, 0x03, 0x00, 0x09, 0x00, 0x0B, 0x30, 0x00, 0x01,
                0x00, 0x15, 0x00, 0x25, 0x01, 0x75, 0x04, 0x95, 0x02, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 2u);
  EXPECT_EQ(r.fields[0].usage, make_usage(kButtonPage, 3));
  EXPECT_EQ(r.fields[1].usage, make_usage(kGenericDesktopPage, 0x30));
}

TEST(HidReportDescriptor, ShortUsagesTakeThePageInForceAtTheMainItem) {
  const Bytes d{0x09, 0x05, 0x05, 0x09, 0x75, 0x01, 0x95, 0x01, 0x25, 0x01, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 1u);
  EXPECT_EQ(r.fields[0].usage, make_usage(kButtonPage, 5));
}

TEST(HidReportDescriptor, LongItemsAreSkipped) {
  const Bytes d{0xFE, 0x03, 0x42, 0xAA, 0xBB, 0xCC,  // a long item with 3 data bytes
                0x05, 0x01, 0x09, 0x30, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 1u);
  EXPECT_EQ(r.fields[0].usage, make_usage(kGenericDesktopPage, 0x30));
}

TEST(HidReportDescriptor, PushAndPopSaveAndRestoreTheGlobals) {
  const Bytes d{0x05, 0x01, 0x75, 0x08, 0x95, 0x01, 0x26, 0xFF, 0x00,        // 8-bit, 0..255, Generic Desktop
                0xA4,                                                        // Push
                0x05, 0x09, 0x75, 0x01, 0x25, 0x01, 0x09, 0x01, 0x81, 0x02,  // one button bit
                0xB4,                                                        // Pop
                0x09, 0x31, 0x81, 0x02};                                     // Y: 8-bit 0..255 again
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 2u);
  EXPECT_EQ(r.fields[0].usage, make_usage(kButtonPage, 1));
  EXPECT_EQ(r.fields[1].usage, make_usage(kGenericDesktopPage, 0x31));
  EXPECT_EQ(r.fields[1].bit_size, 8u);
  EXPECT_EQ(r.fields[1].bit_offset, 1u);
  EXPECT_EQ(r.fields[1].logical_maximum, 255);
}

TEST(HidReportDescriptor, ConstantPaddingAdvancesWithoutAField) {
  const Bytes d{0x05, 0x09, 0x19, 0x01, 0x29, 0x03, 0x25, 0x01, 0x75, 0x01, 0x95, 0x03, 0x81, 0x02,  // 3 buttons
                0x95, 0x05, 0x81, 0x03,                                                              // 5 bits padding
                0x05, 0x01, 0x09, 0x30, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02};       // X
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 4u);
  EXPECT_EQ(r.fields[3].usage, make_usage(kGenericDesktopPage, 0x30));
  EXPECT_EQ(r.fields[3].bit_offset, 8u);
  EXPECT_EQ(r.reports[0].bits, 16u);
}

TEST(HidReportDescriptor, ArrayFieldsKeepTheirUsageList) {
  // Two 8-bit slots, each naming a button 1..8 (value 1 = button 1), as a keyboard does keys.
  const Bytes d{0x05, 0x09, 0x19, 0x01, 0x29, 0x08, 0x15, 0x01, 0x25, 0x08, 0x75, 0x08, 0x95, 0x02, 0x81, 0x00};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 1u);
  const InputField& f = r.fields[0];
  EXPECT_TRUE(f.array);
  EXPECT_EQ(f.count, 2u);
  EXPECT_EQ(f.usage_count(), 8u);
  EXPECT_EQ(f.array_usage(1), make_usage(kButtonPage, 1));
  EXPECT_EQ(f.array_usage(8), make_usage(kButtonPage, 8));
  EXPECT_EQ(f.array_usage(0), 0u);  // outside the logical extent: no usage
  EXPECT_EQ(f.array_usage(9), 0u);
  EXPECT_EQ(r.reports[0].bits, 16u);
}

TEST(HidReportDescriptor, DelimitersKeepTheFirstUsageOfASet) {
  const Bytes d{0x05, 0x01, 0xA9, 0x01, 0x09, 0x31, 0x09, 0x30, 0xA9, 0x00,  // {Y | X}
                0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 1u);
  EXPECT_EQ(r.fields[0].usage, make_usage(kGenericDesktopPage, 0x31));
}

TEST(HidReportDescriptor, SeveralReportIdsKeepSeparateLayouts) {
  const Bytes d{0x05, 0x01, 0x85, 0x02, 0x09, 0x30, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0x85,
                0x07, 0x09, 0x31, 0x75, 0x10, 0x81, 0x02, 0x85, 0x02, 0x09, 0x32, 0x75, 0x08, 0x81, 0x02};
  const ReportDescriptor r = parse_report_descriptor(d);
  ASSERT_EQ(r.reports.size(), 2u);
  EXPECT_EQ(r.report(2)->bits, 16u);
  EXPECT_EQ(r.report(7)->bits, 16u);
  EXPECT_EQ(r.report(3), nullptr);
  EXPECT_EQ(r.fields[2].report_id, 2);
  EXPECT_EQ(r.fields[2].bit_offset, 8u);  // Z continues report 2 after X
  EXPECT_EQ(r.max_report_bytes(), 3u);
}

TEST(HidReportDescriptor, TruncatedItemIsRefusedAtItsOffset) {
  const Bytes d{0x05, 0x01, 0x09, 0x30, 0x26, 0xFF};  // Logical Maximum needs 2 data bytes
  const HidDescriptorError e = hid_desc_error(d);
  EXPECT_EQ(e.offset(), 4u);
  EXPECT_NE(std::string(e.what()).find("byte 4"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("Logical Maximum"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("needs 2 data bytes, only 1 left"), std::string::npos) << e.what();
}

TEST(HidReportDescriptor, ReportCountOverflowIsRefused) {
  // Report Count 0xFFFFFFFF of 32-bit fields: 2^37 bits.
  const Bytes d{0x05, 0x01, 0x09, 0x30, 0x75, 0x20, 0x97, 0xFF, 0xFF, 0xFF, 0xFF, 0x81, 0x02};
  const HidDescriptorError e = hid_desc_error(d);
  EXPECT_EQ(e.offset(), 11u);
  EXPECT_NE(std::string(e.what()).find("report count 4294967295 x report size 32"), std::string::npos) << e.what();
}

TEST(HidReportDescriptor, InvertedUsageRangeIsRefused) {
  const Bytes d{0x05, 0x09, 0x19, 0x0E, 0x29, 0x01, 0x25, 0x01, 0x75, 0x01, 0x95, 0x0E, 0x81, 0x02};
  const HidDescriptorError e = hid_desc_error(d);
  EXPECT_EQ(e.offset(), 4u);  // the Usage Maximum that closed the range
  EXPECT_NE(std::string(e.what()).find("usage maximum 0x01 below usage minimum 0x0E"), std::string::npos) << e.what();
}

TEST(HidReportDescriptor, OtherMalformedDescriptorsNameTheirOffset) {
  struct Case {
    Bytes bytes;
    std::size_t offset;
    const char* says;
  };
  const std::vector<Case> cases{
      {{0x05, 0x09, 0x19, 0x01, 0x75, 0x01, 0x95, 0x01, 0x81, 0x02}, 8, "lone Usage Minimum"},
      {{0x05, 0x01, 0xB4}, 2, "Pop with nothing pushed"},
      {{0x05, 0x01, 0xC0}, 2, "End Collection with no open collection"},
      {{0x05, 0x01, 0x09, 0x05, 0xA1, 0x01}, 6, "ends inside 1 open collection"},
      {{0x85, 0x00}, 0, "report id 0"},
      {{0x09, 0x30, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0x85, 0x01}, 8, "Report ID after input data"},
      {{0x09, 0x30, 0x15, 0x0A, 0x25, 0x05, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02}, 10, "logical minimum 10 above"},
      {{0x76, 0xFF, 0xFF}, 0, "report size 65535"},
      {{0x07, 0x00, 0x00, 0x01, 0x00}, 0, "usage page 0x10000"},
      {{0xD0}, 0, "unknown main item tag 0xD"},
      {{0xC4}, 0, "unknown global item tag 0xC"},
      {{0x05, 0x01, 0xFE, 0x05, 0x00, 0x01}, 2, "long item of 5 data bytes"},
      {{0xFE, 0x01}, 0, "long item header cut short"},
      {{0x05, 0x01, 0x1B, 0x01, 0x00, 0x09, 0x00, 0x2B, 0x05, 0x00, 0x01, 0x00, 0x75, 0x01, 0x95, 0x01, 0x81, 0x02},
       7,
       "crosses usage pages"},
  };
  for (const Case& c : cases) {
    const HidDescriptorError e = hid_desc_error(c.bytes);
    EXPECT_EQ(e.offset(), c.offset) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
  }
}

TEST(HidReportDescriptor, EveryCutOfARealDescriptorParsesOrThrowsWithinIt) {
  const Bytes full = testing::load_hid_fixture("dualshock4_v2_usb.hex");
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Bytes cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    try {
      parse_report_descriptor(cut);
    } catch (const HidDescriptorError& e) {
      EXPECT_LE(e.offset(), n);
    }
  }
}

TEST(HidReportDescriptor, RandomBytesNeverCrashTheParser) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  const Bytes f310 = testing::load_hid_fixture("logitech_f310_dinput.hex");
  for (int round = 0; round < 20000; ++round) {
    Bytes d = f310;  // a real descriptor with a few bytes changed, or pure noise
    if (round % 2 == 0) {
      for (int k = 0; k < 3; ++k) d[rng() % d.size()] = static_cast<std::uint8_t>(rng());
    } else {
      d.resize(rng() % 64);
      for (std::uint8_t& b : d) b = static_cast<std::uint8_t>(rng());
    }
    try {
      const ReportDescriptor r = parse_report_descriptor(d);
      for (const InputReportLayout& l : r.reports) EXPECT_LE(l.bytes(), kMaxReportBytes);
    } catch (const HidDescriptorError& e) {
      EXPECT_LE(e.offset(), d.size());
    }
  }
}

}  // namespace
}  // namespace avar::inputs::hid
