// The streaming device (avar-device protocol): the knots' cubic exact at its knots, a smooth
// motion streamed as knots played within a unit of it, the clock following avar's, a silent link
// or a stop easing to rest, release and hello, damaged frames dropped, and seeded random streams
// (jumps, bursts, silences, clock steps) with no tick outside the range or over a speed or
// acceleration limit.
#include "avar/device/stream_player.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "avar/device/show_export.hpp"

namespace avar::device {
namespace stream_tests {
namespace {

namespace wire = firmware_iface::avar_device;

constexpr std::uint16_t kRate = 200;  // control ticks per second
constexpr std::uint32_t kTickUs = 5000;
constexpr std::uint8_t kCapacity = 8;  // knot frames held

struct Device {
  std::vector<std::array<std::uint8_t, kLimitsSize>> stored;
  std::vector<ChannelLimits> limits;
  std::vector<StreamChannel> channels;
  std::vector<std::uint32_t> times = std::vector<std::uint32_t>(kCapacity);
  std::vector<wire::Knot> knots;
  std::vector<std::uint8_t> frame;
  StreamPlayer player{};
  std::uint32_t now = 0;  // the device's microsecond counter
  std::vector<std::uint8_t> replies;

  explicit Device(int n, std::uint32_t watchdog_us = 300000, std::uint32_t start_us = 0) : now(start_us) {
    stored.resize(static_cast<std::size_t>(n));
    channels.resize(static_cast<std::size_t>(n));
    knots.resize(static_cast<std::size_t>(n) * kCapacity);
    frame.resize(stream_frame_room(static_cast<std::uint8_t>(n)));
    for (int c = 0; c < n; ++c) {
      // -100..100 units, rest 10 * c, 400 units/s, 8000 units/s^2.
      limits.push_back(device_limits({-100, 100}, 10.0 * c, 400, 8000, 0, kRate));
      write_limits(limits.back(), stored[static_cast<std::size_t>(c)].data());
      channels[static_cast<std::size_t>(c)].limits = stored[static_cast<std::size_t>(c)].data();
    }
    EXPECT_EQ(stream_init(player, channels.data(), static_cast<std::uint8_t>(n), times.data(), knots.data(), kCapacity,
                          frame.data(), kRate, watchdog_us),
              kStreamOk);
  }

  void feed(const std::uint8_t* bytes, std::size_t size) {
    std::uint8_t reply[wire::kMaxFrame];
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint16_t n = stream_receive(player, bytes[i], now, reply);
      replies.insert(replies.end(), reply, reply + n);
    }
  }
  void send_time(std::uint32_t host_us) {
    std::uint8_t out[wire::kMaxFrame];
    feed(out, wire::encode_time(host_us, out));
  }
  void send_knots(std::uint32_t at_us, const std::vector<wire::Knot>& k) {
    std::uint8_t out[wire::kMaxFrame];
    feed(out, wire::encode_knots(at_us, k.data(), static_cast<std::uint8_t>(k.size()), out));
  }
  void send(std::size_t (*encode)(std::uint8_t*)) {
    std::uint8_t out[wire::kMaxFrame];
    feed(out, encode(out));
  }
  void tick() {
    stream_tick(player, now);
    now += kTickUs;
  }
};

/// Output units (0..65535 over -100..100) of a channel value.
double to_output(double value) { return (value + 100) / 200 * 65535; }

TEST(StreamPlayer, TheKnotsCubicIsExactAtItsKnotsAndStraightOnAStraightLine) {
  const wire::Knot a{1000, 0}, b{30000, 0};
  EXPECT_EQ(knot_cubic_q8(100, a, 50100, b, 100), 1000 * 256);
  EXPECT_EQ(knot_cubic_q8(100, a, 50100, b, 50100), 30000 * 256);
  EXPECT_EQ(knot_cubic_q8(100, a, 50100, b, 25100), (1000 + 30000) * 128) << "flat ends: the middle is half way";
  // A straight line: 29000 units in 50 ms is 580000 units/s, more than a slope field holds; a
  // slower line: 1000 units in 50 ms = 20000 units/s = slope 2500.
  const wire::Knot c{1000, 2500}, d{2000, 2500};
  for (std::uint32_t t = 0; t <= 50000; t += 1250) {
    const double line = 1000 + 1000.0 * t / 50000;
    EXPECT_NEAR(static_cast<double>(knot_cubic_q8(0, c, 50000, d, t)) / 256.0, line, 0.05) << t;  // the Q8 lerps round down
  }
  EXPECT_EQ(knot_cubic_q8(0xffffff00u, c, 0x0000c250u, d, 0x0000c250u), 2000 * 256) << "across the clock's wrap";
}

TEST(StreamPlayer, PlaysASmoothMotionStreamedAsKnotsWithinAUnit) {
  // avar's side: a 0.5 Hz sine of 60 units on two channels, knots every 50 ms, 150 ms ahead.
  Device device(2, 300000, 123456789u);
  device.send(wire::encode_hello);
  const std::uint32_t host_start = 5000000;
  auto value = [](int c, double t) { return 60 * std::sin(M_PI * t + c); };
  auto slope = [](int c, double t) { return 60 * M_PI * std::cos(M_PI * t + c); };
  auto knots_at = [&](double t) {
    std::vector<wire::Knot> k;
    for (int c = 0; c < 2; ++c)
      k.push_back({static_cast<std::uint16_t>(std::lround(to_output(value(c, t)))),
                   wire::slope_field(static_cast<std::int32_t>(std::lround(slope(c, t) / 200 * 65535)))});
    return k;
  };
  double worst = 0;
  std::uint32_t next_knot_us = 0;
  for (int tick = 0; tick < 6 * kRate; ++tick) {
    const std::uint32_t host_now = host_start + static_cast<std::uint32_t>(tick) * kTickUs;
    if (tick % 10 == 0) device.send_time(host_now);
    // avar sends each knot 150 ms before its time.
    while (next_knot_us <= static_cast<std::uint32_t>(tick) * kTickUs + 150000) {
      device.send_knots(host_start + next_knot_us, knots_at(next_knot_us / 1e6));
      next_knot_us += 50000;
    }
    device.tick();
    if (tick > 2 * kRate) {  // after the soft start from rest
      for (int c = 0; c < 2; ++c) {
        const double t = tick * (kTickUs / 1e6);
        worst = std::max(worst, std::abs(device.channels[static_cast<std::size_t>(c)].output - to_output(value(c, t))));
      }
    }
  }
  EXPECT_EQ(device.player.state, wire::kStreaming);
  EXPECT_EQ(device.player.underruns, 0u);
  EXPECT_LE(worst, 1.0) << "output units of 65535";
}

TEST(StreamPlayer, TheClockFollowsAvarsEarliestMessagesThroughLatency) {
  Device device(1, 0, 4000000000u);  // the device's counter wraps during the run
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> late(0, 5000);  // each message 0 to 5 ms late
  std::uint32_t host = 1000;
  for (int i = 0; i < 400; ++i) {
    device.send_time(host - static_cast<std::uint32_t>(late(rng)));
    for (int t = 0; t < 10; ++t) device.tick();
    host += 10 * kTickUs;
  }
  auto error = [&] { return static_cast<std::int32_t>(stream_time(device.player, device.now) - host); };
  const std::int32_t settled = error();
  EXPECT_LE(std::abs(settled), 600) << "µs: the clock follows the earliest messages, not their mean (2.5 ms late)";
  // One message 30 ms late (a busy PC) moves it by a sixty-fourth of that.
  device.send_time(host - 30000);
  EXPECT_GE(error(), settled - 30000 / 64 - 1);
  // avar ahead by more than the step: set at once; avar started over (far behind): set too.
  device.send_time(host + 90000000u);
  EXPECT_EQ(stream_time(device.player, device.now), host + 90000000u);
  device.send_time(5000);
  EXPECT_EQ(stream_time(device.player, device.now), 5000u);
}

TEST(StreamPlayer, ASilentLinkAStopOrTheKnotsRunningOutNeverLeaveTheFigureMoving) {
  Device device(1, 300000);
  device.send_time(0);
  const std::uint16_t far = static_cast<std::uint16_t>(to_output(90));
  device.send_knots(0, {{far, 0}});
  ASSERT_EQ(device.player.state, wire::kStreaming);
  for (int t = 0; t < 40; ++t) device.tick();  // 200 ms: on its way to the held knot
  EXPECT_EQ(device.player.state, wire::kStreaming);
  EXPECT_GT(device.channels[0].output, to_output(10));
  for (int t = 0; t < 30; ++t) device.tick();  // silent for more than 300 ms
  EXPECT_EQ(device.player.state, wire::kStopping);
  for (int t = 0; t < 400 && device.player.state != wire::kResting; ++t) device.tick();
  EXPECT_EQ(device.player.state, wire::kResting);
  EXPECT_EQ(device.channels[0].state.position, device.limits[0].rest);

  // Streaming again, then kStop: to rest, the knots dropped.
  device.send_time(device.now);
  device.send_knots(device.now, {{far, 0}});
  for (int t = 0; t < 20; ++t) device.tick();
  device.send(wire::encode_stop);
  EXPECT_EQ(device.player.state, wire::kStopping);
  EXPECT_EQ(device.player.count, 0);
  for (int t = 0; t < 400 && device.player.state != wire::kResting; ++t) device.tick();
  EXPECT_EQ(device.player.state, wire::kResting);
}

TEST(StreamPlayer, ReleaseHoldsUntilHelloAndQueriesAnswer) {
  Device device(3);
  device.send(wire::encode_hello);
  wire::Parser parser;
  std::uint8_t parser_buffer[wire::kMaxFrame];
  wire::parser_reset(parser, parser_buffer, wire::kMaxFrame);
  std::vector<std::uint8_t> types;
  auto drain = [&] {
    for (std::uint8_t b : device.replies)
      if (wire::parser_push(parser, b)) types.push_back(parser.type);
    device.replies.clear();
  };
  drain();
  ASSERT_EQ(types, std::vector<std::uint8_t>{wire::kStatus});
  wire::Status status{};
  ASSERT_TRUE(wire::read_status(parser.payload, parser.length, status));
  EXPECT_EQ(status.channel_count, 3);
  EXPECT_EQ(status.rate_hz, kRate);
  EXPECT_EQ(status.knot_capacity, kCapacity);
  EXPECT_EQ(status.state, wire::kResting);

  device.send(wire::encode_release);
  EXPECT_EQ(device.player.state, wire::kReleased);
  device.send_time(0);
  device.send_knots(0, {{0, 0}, {0, 0}, {0, 0}});
  EXPECT_EQ(device.player.state, wire::kReleased) << "knots do not wake a released device";
  device.send(wire::encode_query);
  drain();
  ASSERT_EQ(types.back(), wire::kPositions);
  std::uint16_t outputs[3];
  std::uint8_t count = 0;
  ASSERT_TRUE(wire::read_positions(parser.payload, parser.length, outputs, 3, count));
  EXPECT_EQ(count, 3);
  EXPECT_EQ(outputs[2], device.channels[2].output);
  device.send(wire::encode_hello);
  EXPECT_EQ(device.player.state, wire::kResting);
}

TEST(StreamPlayer, AFaultOfTheDevicesOwnHoldsThroughEveryMessageAndSaysSo) {
  Device device(2);
  device.send_time(0);
  device.send_knots(0, {{60000, 0}, {60000, 0}});
  device.send_knots(100000, {{60000, 0}, {60000, 0}});
  for (int t = 0; t < 5; ++t) device.tick();
  stream_fault(device.player);
  EXPECT_EQ(device.player.state, wire::kFault);
  EXPECT_TRUE(device.channels[0].released && device.channels[1].released);
  const std::uint16_t frozen = device.channels[0].output;
  device.send(wire::encode_hello);
  device.send(wire::encode_release);
  device.send(wire::encode_stop);
  device.send_knots(200000, {{0, 0}, {0, 0}});
  for (int t = 0; t < 5; ++t) device.tick();
  EXPECT_EQ(device.player.state, wire::kFault) << "hello, release, stop and knots leave a fault as it is";
  EXPECT_TRUE(device.channels[0].released);
  EXPECT_EQ(device.channels[0].output, frozen);
  wire::Parser parser;
  std::uint8_t parser_buffer[wire::kMaxFrame];
  wire::parser_reset(parser, parser_buffer, wire::kMaxFrame);
  wire::Status status{};
  for (std::uint8_t b : device.replies)
    if (wire::parser_push(parser, b) && parser.type == wire::kStatus) {
      ASSERT_TRUE(wire::read_status(parser.payload, parser.length, status));
    }
  EXPECT_EQ(status.state, wire::kFault) << "hello's status tells avar";
}

TEST(StreamPlayer, AnswersFitTheirRoom) {
  for (const int n : {1, 3, 8, 11}) {  // rest 10 * c stays in range
    Device device(n);
    std::uint8_t out[wire::kMaxFrame];
    std::vector<std::uint8_t> reply(wire::kMaxFrame, 0xee);
    for (std::size_t (*encode)(std::uint8_t*) : {wire::encode_hello, wire::encode_query}) {
      const std::size_t size = encode(out);
      std::uint16_t answered = 0;
      for (std::size_t i = 0; i < size; ++i) answered = stream_receive(device.player, out[i], 0, reply.data());
      EXPECT_GT(answered, 0);
      EXPECT_LE(answered, stream_reply_room(static_cast<std::uint8_t>(n))) << n << " channels";
    }
  }
}

TEST(StreamPlayer, DamagedFramesAreDroppedWhole) {
  Device device(1);
  device.send_time(0);
  std::uint8_t out[wire::kMaxFrame];
  const wire::Knot k{60000, 0};
  const std::size_t size = wire::encode_knots(0, &k, 1, out);
  out[6] ^= 0x40;  // a bit of the time
  device.feed(out, size);
  EXPECT_EQ(device.player.state, wire::kResting);
  EXPECT_EQ(device.player.parser.bad_frames, 1u);
  const wire::Knot two[] = {{1, 0}, {2, 0}};
  device.feed(out, wire::encode_knots(0, two, 2, out));
  EXPECT_EQ(device.player.state, wire::kResting) << "a frame for another channel count";
}

// Whatever avar sends, the device's outputs stay in the range and within its speed and
// acceleration: random knots (jumps across the range, wild slopes), bursts and silences, clock
// steps, stops and releases, over 2 * 10^5 ticks.
TEST(StreamPlayer, RandomStreamsNeverBreakALimit) {
  const unsigned seed = 33;
  std::mt19937 rng(seed);
  Device device(3, 250000, static_cast<std::uint32_t>(rng()));
  std::uniform_int_distribution<int> value(0, 65535), slope(-32768, 32767), what(0, 99), gap(1, 200000);
  std::vector<LimiterState> last;
  for (const StreamChannel& c : device.channels) last.push_back(c.state);
  std::uint32_t host = static_cast<std::uint32_t>(rng());
  std::uint32_t next_knot = host;
  for (int tick = 0; tick < 200000; ++tick) {
    const int w = what(rng);
    if (w < 8) device.send_time(host);
    if (w == 8) device.send_time(host + static_cast<std::uint32_t>(gap(rng)) * 100u);  // a clock step
    if (w >= 10 && w < 30) {
      std::vector<wire::Knot> k;
      for (int c = 0; c < 3; ++c) k.push_back({static_cast<std::uint16_t>(value(rng)), static_cast<std::int16_t>(slope(rng))});
      device.send_knots(next_knot, k);
      next_knot += static_cast<std::uint32_t>(gap(rng));
      if (w == 29) next_knot = host;  // avar starting over
    }
    if (w == 30 && tick % 7 == 0) device.send(wire::encode_stop);
    if (w == 31 && tick % 97 == 0) device.send(wire::encode_release);
    if (w == 32) device.send(wire::encode_hello);
    device.tick();
    host += kTickUs;
    for (std::size_t c = 0; c < device.channels.size(); ++c) {
      const ChannelLimits& l = device.limits[c];
      const LimiterState& s = device.channels[c].state;
      ASSERT_GE(s.position, l.low) << "seed " << seed << " tick " << tick;
      ASSERT_LE(s.position, l.high) << "seed " << seed << " tick " << tick;
      ASSERT_LE(std::abs(s.position - last[c].position), l.speed) << "seed " << seed << " tick " << tick;
      ASSERT_LE(std::abs(s.velocity - last[c].velocity), l.accel) << "seed " << seed << " tick " << tick;
      last[c] = s;
    }
  }
}

}  // namespace
}  // namespace stream_tests
}  // namespace avar::device
