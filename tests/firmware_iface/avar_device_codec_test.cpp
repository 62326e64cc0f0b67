// The avar-device streaming protocol's frames: golden bytes from docs/protocols/avar-device.md,
// round trips, and the parser finding good frames among noise and damaged frames.
#include "avar/firmware_iface/avar_device_codec.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace avar::firmware_iface::avar_device {
namespace stream_tests {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes framed(std::size_t size, const std::uint8_t* out) { return Bytes(out, out + size); }

TEST(AvarDeviceCodec, CrcIsCcittFalse) {
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc16(0xffff, check, sizeof check), 0x29b1);
}

TEST(AvarDeviceCodec, GoldenFramesFromTheProtocolPage) {
  std::uint8_t out[kMaxFrame];
  EXPECT_EQ(framed(encode_hello(out), out), (Bytes{0xa5, 0x01, 0x01, 0x01, 0xbc, 0xd8}));
  EXPECT_EQ(framed(encode_time(1500000, out), out), (Bytes{0xa5, 0x02, 0x04, 0x60, 0xe3, 0x16, 0x00, 0x30, 0x05}));
  const Knot knots[] = {{32768, -125}, {65535, 4000}};
  EXPECT_EQ(framed(encode_knots(2000000, knots, 2, out), out),
            (Bytes{0xa5, 0x03, 0x0d, 0x80, 0x84, 0x1e, 0x00, 0x02, 0x00, 0x80, 0x83, 0xff, 0xff, 0xff, 0xa0, 0x0f, 0x7b, 0x91}));
  EXPECT_EQ(framed(encode_stop(out), out), (Bytes{0xa5, 0x04, 0x00, 0xcb, 0xd1}));
  EXPECT_EQ(framed(encode_release(out), out), (Bytes{0xa5, 0x05, 0x00, 0xfa, 0xe2}));
  EXPECT_EQ(framed(encode_query(out), out), (Bytes{0xa5, 0x06, 0x00, 0xa9, 0xb7}));
  const Status status{1, 8, 200, 16, kStreaming, 3, 2000000};
  EXPECT_EQ(framed(encode_status(status, out), out),
            (Bytes{0xa5, 0x81, 0x0c, 0x01, 0x08, 0xc8, 0x00, 0x10, 0x01, 0x03, 0x00, 0x80, 0x84, 0x1e, 0x00, 0xf7, 0xa7}));
  const std::uint16_t outputs[] = {100, 65535};
  EXPECT_EQ(framed(encode_positions(outputs, 2, out), out), (Bytes{0xa5, 0x82, 0x05, 0x02, 0x64, 0x00, 0xff, 0xff, 0x7a, 0xb3}));
}

TEST(AvarDeviceCodec, RefusesWhatDoesNotFit) {
  std::uint8_t out[kMaxFrame + 8];
  Knot knots[kMaxChannels + 1] = {};
  EXPECT_EQ(encode_knots(0, knots, 0, out), 0u);
  EXPECT_EQ(encode_knots(0, knots, kMaxChannels + 1, out), 0u);
  EXPECT_EQ(encode_knots(0, knots, kMaxChannels, out), kOverhead + 5 + 4 * kMaxChannels);
  std::uint8_t payload[kMaxPayload + 1] = {};
  EXPECT_EQ(encode_frame(kTime, payload, kMaxPayload + 1, out), 0u);
}

TEST(AvarDeviceCodec, SlopeFieldRoundsAndSaturates) {
  EXPECT_EQ(slope_field(0), 0);
  EXPECT_EQ(slope_field(3), 0);
  EXPECT_EQ(slope_field(4), 1);
  EXPECT_EQ(slope_field(-4), -1);
  EXPECT_EQ(slope_field(-3), 0);
  EXPECT_EQ(slope_field(800), 100);
  EXPECT_EQ(slope_field(10000000), 32767);
  EXPECT_EQ(slope_field(-10000000), -32768);
}

struct Frame {
  std::uint8_t type;
  Bytes payload;
};

std::vector<Frame> parse_all(Parser& parser, const Bytes& bytes) {
  std::vector<Frame> frames;
  for (std::uint8_t b : bytes)
    if (parser_push(parser, b)) frames.push_back({parser.type, Bytes(parser.payload, parser.payload + parser.length)});
  return frames;
}

// A device keeps a parser only as long as its longest message: a longer frame (another device's
// knots) counts as bad and is skipped whole, and the frames around it are found.
TEST(AvarDeviceCodec, AParserWithLittleRoomSkipsLongerFramesWhole) {
  std::uint8_t out[kMaxFrame];
  Bytes stream;
  auto add = [&](std::size_t n) { stream.insert(stream.end(), out, out + n); };
  const Knot two[] = {{100, 1}, {200, -2}};
  Knot many[20] = {};
  many[0].value = 0xa5a5;  // start bytes inside the long frame
  add(encode_knots(5000, two, 2, out));
  add(encode_knots(6000, many, 20, out));
  add(encode_time(7000, out));
  add(encode_knots(8000, two, 2, out));
  Parser parser;
  std::uint8_t buffer[kOverhead + 5 + 4 * 2];
  parser_reset(parser, buffer, sizeof buffer);
  const std::vector<Frame> frames = parse_all(parser, stream);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].type, kKnots);
  EXPECT_EQ(frames[1].type, kTime);
  EXPECT_EQ(frames[2].type, kKnots);
  EXPECT_GE(parser.bad_frames, 1u);
}

TEST(AvarDeviceCodec, EveryMessageRoundTrips) {
  std::uint8_t out[kMaxFrame];
  Parser parser;
  std::uint8_t buffer[kMaxFrame];
  parser_reset(parser, buffer, kMaxFrame);
  Bytes stream;
  auto add = [&](std::size_t n) { stream.insert(stream.end(), out, out + n); };
  add(encode_hello(out));
  add(encode_time(0xfffffff0u, out));
  Knot knots[3] = {{0, -32768}, {12345, 32767}, {65535, 0}};
  add(encode_knots(77, knots, 3, out));
  const Status status{1, 3, 100, 8, kStopping, 65535, 42};
  add(encode_status(status, out));
  const std::uint16_t outputs[] = {1, 2, 3};
  add(encode_positions(outputs, 3, out));
  const std::vector<Frame> frames = parse_all(parser, stream);
  ASSERT_EQ(frames.size(), 5u);
  std::uint8_t version = 0;
  ASSERT_TRUE(read_hello(frames[0].payload.data(), static_cast<std::uint8_t>(frames[0].payload.size()), version));
  EXPECT_EQ(version, kVersion);
  std::uint32_t time = 0;
  ASSERT_TRUE(read_time(frames[1].payload.data(), static_cast<std::uint8_t>(frames[1].payload.size()), time));
  EXPECT_EQ(time, 0xfffffff0u);
  Knot back[3];
  std::uint8_t count = 0;
  ASSERT_TRUE(read_knots(frames[2].payload.data(), static_cast<std::uint8_t>(frames[2].payload.size()), time, back, 3, count));
  EXPECT_EQ(time, 77u);
  ASSERT_EQ(count, 3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(back[c].value, knots[c].value);
    EXPECT_EQ(back[c].slope, knots[c].slope);
  }
  EXPECT_FALSE(read_knots(frames[2].payload.data(), static_cast<std::uint8_t>(frames[2].payload.size()), time, back, 2, count))
      << "more channels than the reader holds";
  Status s{};
  ASSERT_TRUE(read_status(frames[3].payload.data(), static_cast<std::uint8_t>(frames[3].payload.size()), s));
  EXPECT_EQ(s.channel_count, 3);
  EXPECT_EQ(s.rate_hz, 100);
  EXPECT_EQ(s.knot_capacity, 8);
  EXPECT_EQ(s.state, kStopping);
  EXPECT_EQ(s.bad_frames, 65535);
  EXPECT_EQ(s.time_us, 42u);
  std::uint16_t got[3];
  ASSERT_TRUE(read_positions(frames[4].payload.data(), static_cast<std::uint8_t>(frames[4].payload.size()), got, 3, count));
  EXPECT_EQ(got[2], 3);
  EXPECT_EQ(parser.bad_frames, 0u);
  EXPECT_EQ(parser.skipped, 0u);
}

// Seeded noise and damage: every frame the parser returns is one that was sent, and every frame
// sent whole after a damaged one is found (the parser re-synchronises inside the damage).
TEST(AvarDeviceCodec, FindsTheGoodFramesAmongNoiseAndDamage) {
  const unsigned seed = 20261207;
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255), kind(0, 3), channels(1, kMaxChannels);
  std::uint8_t out[kMaxFrame];
  Parser parser;
  std::uint8_t buffer[kMaxFrame];
  parser_reset(parser, buffer, kMaxFrame);
  std::size_t sent_whole = 0, found = 0;
  for (int round = 0; round < 2000; ++round) {
    Knot knots[kMaxChannels];
    const int n = channels(random);
    for (int c = 0; c < n; ++c)
      knots[c] = {static_cast<std::uint16_t>(byte(random) * 257), static_cast<std::int16_t>(byte(random) - 128)};
    const std::uint32_t time = static_cast<std::uint32_t>(round) * 50000u;
    const std::size_t size = encode_knots(time, knots, static_cast<std::uint8_t>(n), out);
    Bytes bytes(out, out + size);
    const int what = kind(random);
    if (what == 1) bytes[static_cast<std::size_t>(byte(random)) % size] ^= static_cast<std::uint8_t>(1 + byte(random) % 255);
    if (what == 2) bytes.resize(static_cast<std::size_t>(byte(random)) % size);              // cut short
    if (what == 3) bytes.insert(bytes.begin(), 3, static_cast<std::uint8_t>(byte(random)));  // noise before
    std::vector<Frame> frames = parse_all(parser, bytes);
    if (what != 0) {
      // A damaged frame (or a start byte in the noise) may promise more bytes than it has: the
      // parser takes the next bytes into it, fails its CRC and looks again inside them. Stop
      // frames carry it past the largest frame before the next round.
      const std::size_t stop = encode_stop(out);
      for (int i = 0; i < 60; ++i)
        for (Frame& f : parse_all(parser, Bytes(out, out + stop))) frames.push_back(std::move(f));
    }
    for (const Frame& f : frames) {
      if (f.type != kKnots) continue;
      std::uint32_t t = 0;
      Knot back[kMaxChannels];
      std::uint8_t count = 0;
      ASSERT_TRUE(read_knots(f.payload.data(), static_cast<std::uint8_t>(f.payload.size()), t, back, kMaxChannels, count))
          << "seed " << seed;
      ASSERT_EQ(t, time) << "seed " << seed << ": a frame that was not sent";
      ++found;
    }
    if (what == 0 || what == 3) ++sent_whole;
  }
  EXPECT_EQ(found, sent_whole) << "seed " << seed;
  EXPECT_GT(parser.bad_frames, 0u);
}

}  // namespace
}  // namespace stream_tests
}  // namespace avar::firmware_iface::avar_device
