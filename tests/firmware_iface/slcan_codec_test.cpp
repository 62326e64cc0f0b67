// SLCAN codec against the test vectors of shared/protocols/slcan.md (L1..L9), both ways, and its
// validation, extensions and round trips.
#include "avar/firmware_iface/slcan_codec.hpp"

#include <array>
#include <gtest/gtest.h>
#include <random>
#include <string>
#include <vector>

namespace avar::firmware_iface::slcan {
namespace {

std::span<const std::uint8_t> slcan_text(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

std::string slcan_encoded(const CanFrame& f, int timestamp_ms = -1) {
  std::array<std::uint8_t, kMaxLineLength> out{};
  const std::size_t n = encode_frame(out, f, timestamp_ms);
  return {reinterpret_cast<const char*>(out.data()), n};
}

/// Parses a whole line as it arrives, CR included (the CR is cut off first).
Line slcan_parsed(const std::string& with_cr) {
  EXPECT_EQ(with_cr.back(), '\r');
  return parse_line(slcan_text(with_cr.substr(0, with_cr.size() - 1)));
}

CanFrame slcan_frame(std::uint32_t id, std::vector<std::uint8_t> bytes, bool extended = false) {
  return can_data_frame(id, bytes, extended);
}

struct SlcanVector {
  const char* name;
  std::string line;
  CanFrame frame;
};

std::vector<SlcanVector> slcan_vectors() {
  const std::vector<std::uint8_t> eight{0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF};
  return {
      {"L1", "t1230\r", slcan_frame(0x123, {})},
      {"L2", "t4563112233\r", slcan_frame(0x456, {0x11, 0x22, 0x33})},
      {"L3", "T12ABCDEF2AA55\r", slcan_frame(0x12ABCDEF, {0xAA, 0x55}, true)},
      {"L4", "r1230\r", can_remote_frame(0x123, 0)},
      {"L5", "t34580123456789ABCDEF\r", slcan_frame(0x345, eight)},
      {"L6", "T1234567880123456789ABCDEF\r", slcan_frame(0x12345678, eight, true)},
      {"L7", "t00231199FF\r", slcan_frame(0x002, {0x11, 0x99, 0xFF})},
      {"L9", "t02C80000803F00000000\r", slcan_frame(0x02C, {0x00, 0x00, 0x80, 0x3F, 0x00, 0x00, 0x00, 0x00})},
  };
}

TEST(SlcanCodec, EncodesEveryFrameVectorOfTheNote) {
  for (const auto& v : slcan_vectors()) EXPECT_EQ(slcan_encoded(v.frame), v.line) << v.name;
}

TEST(SlcanCodec, DecodesEveryFrameVectorOfTheNote) {
  for (const auto& v : slcan_vectors()) {
    const Line line = slcan_parsed(v.line);
    ASSERT_EQ(line.kind, LineKind::frame) << v.name;
    EXPECT_EQ(line.frame, v.frame) << v.name;
    EXPECT_EQ(line.timestamp_ms, -1) << v.name;
  }
}

TEST(SlcanCodec, DecodesTheRepliesOfTheNote) {
  EXPECT_EQ(slcan_parsed("z\r").kind, LineKind::ack);   // L5, L7
  EXPECT_EQ(slcan_parsed("Z\r").kind, LineKind::ack);   // L6
  EXPECT_EQ(slcan_parsed("\r").kind, LineKind::empty);  // L8's answer to Z1
  const Line status = slcan_parsed("F0A\r");
  EXPECT_EQ(status.kind, LineKind::status);
  EXPECT_EQ(status.flags, 0x0A);
  EXPECT_EQ(slcan_parsed("V1013\r").kind, LineKind::version);
  EXPECT_EQ(slcan_parsed("NA123\r").kind, LineKind::serial);
}

TEST(SlcanCodec, AcceptsLowerCaseHexAndWritesUpperCase) {
  const Line line = slcan_parsed("t02c80000803f00000000\r");
  ASSERT_EQ(line.kind, LineKind::frame);
  EXPECT_EQ(slcan_encoded(line.frame), "t02C80000803F00000000\r");
  EXPECT_EQ(slcan_parsed("T12abcdef2aa55\r").frame, slcan_frame(0x12ABCDEF, {0xAA, 0x55}, true));
}

TEST(SlcanCodec, TimestampsAreFourHexDigitsOfRollingMilliseconds) {
  const Line line = slcan_parsed("T1111222281122334455667788EA5F\r");  // the Linux driver's longest line
  ASSERT_EQ(line.kind, LineKind::frame);
  EXPECT_EQ(line.timestamp_ms, 59'999);
  EXPECT_EQ(line.frame.dlc, 8);
  EXPECT_EQ(slcan_encoded(line.frame, 59'999), "T1111222281122334455667788EA5F\r");
  EXPECT_EQ(slcan_encoded(line.frame, 59'999).size(), kMaxLineLength);
  EXPECT_EQ(slcan_encoded(slcan_frame(0x123, {}), 60'005), "t12300005\r");  // wraps every minute
  EXPECT_EQ(slcan_parsed("r12380010\r").timestamp_ms, 0x10);                // RTR: DLC 8, no data, a timestamp
  // The line lengths of the note: 22 characters for 8 bytes (26 with a timestamp: 22 + 4; the
  // note's "27" miscounts); 27 extended.
  EXPECT_EQ(slcan_encoded(slcan_frame(0x345, std::vector<std::uint8_t>(8))).size(), 22u);
  EXPECT_EQ(slcan_encoded(slcan_frame(0x345, std::vector<std::uint8_t>(8)), 0).size(), 26u);
  EXPECT_EQ(slcan_encoded(slcan_frame(0x345, std::vector<std::uint8_t>(8), true)).size(), 27u);
}

TEST(SlcanCodec, RejectsWhatTheNoteSaysIsInvalid) {
  for (const char* bad : {
           "t8000\r",       // standard id above 7FF
           "T200000000\r",  // extended id above 1FFFFFFF
           "t1239\r",       // DLC 9
           "t123A\r",       // DLC not a decimal digit
           "t123211\r",     // one data pair short
           "t12321122A\r",  // half a pair too many
           "t1232112G\r",   // not hex
           "r1232AA\r",     // remote frames carry no data (4 digits would be a timestamp)
           "t12\r",         // truncated
           "t12300\r",      // a timestamp must be 4 digits
           "x\r",           // unknown letter
           "zz\r",          // an ack is one letter
           "F0\r",          // status is 2 hex digits
           "sx000000\r",    // unknown state letter
           "sa05703\r",     // counters are 3 digits each
           "sa05a033\r",    // decimal counters
           "e2a\r",         // count says 2 letters, 1 given
           "e1x\r",         // unknown error letter
           "e0\r",          // no error
       })
    EXPECT_EQ(slcan_parsed(bad).kind, LineKind::malformed) << bad;
}

TEST(SlcanCodec, EncoderRefusesInvalidFramesAndShortBuffers) {
  std::array<std::uint8_t, kMaxLineLength> out{};
  CanFrame f = slcan_frame(0x800, {});
  EXPECT_EQ(encode_frame(out, f), 0u);  // id out of range
  f = slcan_frame(0x123, {});
  f.dlc = 9;
  EXPECT_EQ(encode_frame(out, f), 0u);
  f.dlc = 0;
  f.error = true;
  EXPECT_EQ(encode_frame(out, f), 0u);  // error frames are not transmitted
  std::array<std::uint8_t, 5> short_buffer{};
  EXPECT_EQ(encode_frame(short_buffer, slcan_frame(0x123, {})), 0u);  // "t1230" + CR is 6
  std::array<std::uint8_t, 6> exact{};
  EXPECT_EQ(encode_frame(exact, slcan_frame(0x123, {})), 6u);
}

TEST(SlcanCodec, LinuxStateLinesAreErrorFramesWithCounters) {
  const Line active = slcan_parsed("sa057033\r");
  ASSERT_EQ(active.kind, LineKind::error_frame);
  EXPECT_TRUE(active.frame.error);
  EXPECT_EQ(active.frame.id, 0u);       // back to error active: no class remains
  EXPECT_EQ(active.frame.data[6], 33);  // TX counter
  EXPECT_EQ(active.frame.data[7], 57);  // RX counter
  EXPECT_EQ(slcan_parsed("sw096000\r").frame.id, kCanErrorWarning);
  EXPECT_EQ(slcan_parsed("sp000128\r").frame.id, kCanErrorPassive);
  const Line bus_off = slcan_parsed("sb000256\r");
  EXPECT_EQ(bus_off.frame.id, kCanErrorBusOff);
  EXPECT_EQ(bus_off.frame.data[6], 255);  // clamped
}

TEST(SlcanCodec, LinuxErrorLinesAreErrorFramesByClass) {
  EXPECT_EQ(slcan_parsed("e1a\r").frame.id, kCanErrorAck);
  for (const char* protocol : {"e1b\r", "e1B\r", "e1c\r", "e1f\r", "e1s\r"})
    EXPECT_EQ(slcan_parsed(protocol).frame.id, kCanErrorProtocol) << protocol;
  EXPECT_EQ(slcan_parsed("e2oO\r").frame.id, kCanErrorOverrun);
  EXPECT_EQ(slcan_parsed("e3asO\r").frame.id, kCanErrorAck | kCanErrorProtocol | kCanErrorOverrun);
}

TEST(SlcanCodec, ErrorLinesRoundTripEveryClassCombination) {
  const std::uint32_t all =
      kCanErrorProtocol | kCanErrorAck | kCanErrorWarning | kCanErrorPassive | kCanErrorBusOff | kCanErrorOverrun;
  for (std::uint32_t classes = 1; classes <= all; ++classes) {
    if (classes & ~all) continue;
    CanFrame f;
    f.error = true;
    f.id = classes;
    std::array<std::uint8_t, 2 * kMaxLineLength> out{};
    const std::size_t n = encode_error_lines(out, f, 5, 200);
    ASSERT_GT(n, 0u) << classes;
    // Split into lines and decode each; the state line keeps the most severe state only.
    std::uint32_t decoded = 0;
    std::size_t begin = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (out[i] != kCr) continue;
      const Line line = parse_line(std::span<const std::uint8_t>(out.data() + begin, i - begin));
      ASSERT_EQ(line.kind, LineKind::error_frame) << classes;
      decoded |= line.frame.id;
      begin = i + 1;
    }
    EXPECT_EQ(begin, n);
    std::uint32_t expected = classes & (kCanErrorProtocol | kCanErrorAck | kCanErrorOverrun);
    expected |= (classes & kCanErrorBusOff)    ? kCanErrorBusOff
                : (classes & kCanErrorPassive) ? kCanErrorPassive
                                               : (classes & kCanErrorWarning);
    EXPECT_EQ(decoded, expected) << classes;
  }
  CanFrame restarted;
  restarted.error = true;
  restarted.id = kCanErrorRestarted;
  std::array<std::uint8_t, kMaxLineLength> out{};
  const std::size_t n = encode_error_lines(out, restarted, 0, 0);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data()), n), "sa000000\r");
}

TEST(SlcanCodec, BitrateCodesFollowTheLinuxDriver) {
  const std::array<int, 9> rates{10'000, 20'000, 50'000, 100'000, 125'000, 250'000, 500'000, 800'000, 1'000'000};
  for (int code = 0; code < 9; ++code) {
    EXPECT_EQ(bitrate_code(rates[static_cast<std::size_t>(code)]), code);
    EXPECT_EQ(bitrate_of_code(code), rates[static_cast<std::size_t>(code)]);
  }
  EXPECT_EQ(bitrate_code(800'000), 7);
  EXPECT_EQ(bitrate_code(750'000), -1);  // python-can's S7 quirk
  EXPECT_EQ(bitrate_code(83'333), -1);   // python-can's S9
  EXPECT_EQ(bitrate_of_code(9), 0);
  EXPECT_EQ(bitrate_of_code(-1), 0);
  std::array<std::uint8_t, 3> out{};
  ASSERT_EQ(encode_bitrate_command(out, 1'000'000), 3u);
  EXPECT_EQ(std::string(out.begin(), out.end()), "S8\r");
  EXPECT_EQ(encode_bitrate_command(out, 750'000), 0u);
}

TEST(SlcanCodec, LawicelStatusFlagsMapToErrorClasses) {
  EXPECT_EQ(error_classes_of_status(0), 0u);
  EXPECT_EQ(error_classes_of_status(kRxFifoFull), kCanErrorOverrun);
  EXPECT_EQ(error_classes_of_status(kDataOverrun), kCanErrorOverrun);
  EXPECT_EQ(error_classes_of_status(kErrorWarning), kCanErrorWarning);
  EXPECT_EQ(error_classes_of_status(kErrorPassive), kCanErrorPassive);
  EXPECT_EQ(error_classes_of_status(kBusError), kCanErrorProtocol);
  EXPECT_EQ(error_classes_of_status(kTxFifoFull | kArbitrationLost), 0u);
  for (std::uint32_t c : {kCanErrorOverrun, kCanErrorWarning, kCanErrorPassive, kCanErrorProtocol})
    EXPECT_EQ(error_classes_of_status(status_of_error_classes(c)), c);
  EXPECT_EQ(status_of_error_classes(kCanErrorBusOff), kBusError | kErrorPassive);
}

TEST(SlcanCodec, RandomFramesRoundTrip) {
  const std::uint32_t seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  for (int i = 0; i < 2000; ++i) {
    CanFrame f;
    f.extended = rng() % 2;
    f.rtr = rng() % 4 == 0;
    f.id = static_cast<std::uint32_t>(rng()) & (f.extended ? kCanMaxExtendedId : kCanMaxStandardId);
    f.dlc = static_cast<std::uint8_t>(rng() % 9);
    if (!f.rtr)
      for (std::uint8_t b = 0; b < f.dlc; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    const int timestamp = rng() % 2 ? static_cast<int>(rng() % kTimestampModulo) : -1;
    const std::string line = slcan_encoded(f, timestamp);
    ASSERT_FALSE(line.empty());
    const Line back = slcan_parsed(line);
    ASSERT_EQ(back.kind, LineKind::frame) << line;
    EXPECT_EQ(back.frame, f) << line;
    EXPECT_EQ(back.timestamp_ms, timestamp) << line;
  }
}

}  // namespace
}  // namespace avar::firmware_iface::slcan
