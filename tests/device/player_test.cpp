// The device's player and limiter: a soft start from rest, a show within the limits played
// exactly once caught up, stop easing to rest, and 10^4 seeded switches between random shows
// (and stops) mid-motion with no tick over a speed or acceleration limit or outside the range.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "avar/device/player.hpp"
#include "avar/device/show_export.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace avar::device {
namespace {

using playback::Interpolation;

constexpr std::uint32_t kRate = 200;  // control ticks per second

/// A random show of `channels` channels: Bezier, linear, sine or elastic keys over the range
/// -100..100, 1 to 4 s long, some looping.
std::vector<std::uint8_t> random_show(std::mt19937& rng, int channels) {
  std::uniform_real_distribution<double> u(0, 1);
  playback::Show show;
  show.name = "random";
  show.duration = 1 + static_cast<double>(rng() % 4);
  show.loop = rng() % 3 == 0;
  std::vector<ImageChannel> image_channels;
  const Interpolation families[] = {Interpolation::bezier, Interpolation::linear, Interpolation::sine, Interpolation::elastic,
                                    Interpolation::step};
  for (int c = 0; c < channels; ++c) {
    std::vector<playback::RawKey> keys;
    for (double t = 0; t <= show.duration + 1e-9; t += 0.25 * (1 + static_cast<double>(rng() % 4))) {
      playback::RawKey k;
      k.time = t;
      k.value = -100 + 200 * u(rng);
      k.interpolation = families[rng() % 5];
      keys.push_back(k);
    }
    playback::RawCurve raw(std::move(keys), {"random.yaml", 1, 1});
    playback::Curve curve = playback::Curve::build(raw);
    const std::string name = "c" + std::to_string(c);
    show.tracks.push_back({name, std::move(raw), std::move(curve), {}});
    image_channels.push_back({name, {-100, 100}});
  }
  return encode_show_image(show, image_channels).bytes;
}

/// Limits as the player reads them (stored bytes), kept beside the numbers for the checks.
struct StoredLimits {
  ChannelLimits limits;
  std::array<std::uint8_t, kLimitsSize> bytes{};
  explicit StoredLimits(const ChannelLimits& l) : limits(l) { write_limits(l, bytes.data()); }
};

struct Figure {
  std::vector<std::vector<std::uint8_t>> images;
  std::vector<PlayerShow> shows;
  std::vector<PlayerChannel> channels;
  std::vector<std::unique_ptr<StoredLimits>> limits;
  Player player{};
};

void set_up(Figure& f, std::mt19937& rng, int channels, int shows) {
  for (int s = 0; s < shows; ++s) f.images.push_back(random_show(rng, channels));
  for (const auto& image : f.images) f.shows.push_back({image.data(), static_cast<std::uint32_t>(image.size())});
  f.channels.resize(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    f.limits.push_back(std::make_unique<StoredLimits>(
        device_limits({-100, 100}, -50 + 10 * c, 150 + 100 * c, 600 + 400 * c, c == 0 ? 0.0 : 5.0, kRate)));
    f.channels[static_cast<std::size_t>(c)].limits = f.limits.back()->bytes.data();
  }
  ASSERT_EQ(player_init(f.player, f.channels.data(), static_cast<std::uint8_t>(channels), f.shows.data(),
                        static_cast<std::uint8_t>(shows), kRate),
            kPlayerOk);
}

TEST(DevicePlayer, StartsAtRestAndEasesBackToRestOnStop) {
  std::mt19937 rng(5);
  Figure f;
  set_up(f, rng, 3, 2);
  for (const PlayerChannel& c : f.channels) {
    EXPECT_EQ(c.state.position, read_limits(c.limits).rest);
    EXPECT_EQ(c.state.velocity, 0);
  }
  ASSERT_EQ(player_start(f.player, 1), kPlayerOk);
  for (int i = 0; i < 100; ++i) player_tick(f.player);
  player_stop(f.player);
  EXPECT_EQ(f.player.mode, kPlayerStopping);
  for (int i = 0; i < 5000 && f.player.mode != kPlayerResting; ++i) player_tick(f.player);
  EXPECT_EQ(f.player.mode, kPlayerResting);
  for (const PlayerChannel& c : f.channels) EXPECT_EQ(c.state.position, read_limits(c.limits).rest);
  EXPECT_EQ(player_start(f.player, 2), kPlayerBadShow);
}

// A slow sine within every limit: once the soft start has caught up, each output is the engine's.
TEST(DevicePlayer, PlaysAShowWithinItsLimitsExactlyOnceCaughtUp) {
  playback::Show show;
  show.name = "slow";
  show.duration = 8;
  std::vector<playback::RawKey> keys;
  for (int i = 0; i <= 8; ++i) {
    playback::RawKey k;
    k.time = i;
    k.value = i % 2 ? 40 : -40;
    k.interpolation = Interpolation::sine;
    k.easing = playback::Easing::ease_in_out;
    keys.push_back(k);
  }
  playback::RawCurve raw(std::move(keys), {"slow.yaml", 1, 1});
  playback::Curve curve = playback::Curve::build(raw);
  show.tracks.push_back({"neck", raw, curve, {}});
  const std::vector<std::uint8_t> image = encode_show_image(show, {{"neck", {-100, 100}}}).bytes;
  const PlayerShow shows[] = {{image.data(), static_cast<std::uint32_t>(image.size())}};
  PlayerChannel channel{};
  const StoredLimits limits(device_limits({-100, 100}, 0, 200, 1000, 0, kRate));  // the sine asks 126 deg/s, 400 deg/s^2
  channel.limits = limits.bytes.data();
  Player player{};
  ASSERT_EQ(player_init(player, &channel, 1, shows, 1, kRate), kPlayerOk);
  ASSERT_EQ(player_start(player, 0), kPlayerOk);
  Channel reference;
  ASSERT_TRUE(open_channel(image.data(), static_cast<std::uint32_t>(image.size()), 0, reference));
  SegmentCache cache;
  reset_cache(cache);
  int exact = 0;
  for (std::uint32_t i = 0; i < 8 * kRate; ++i) {
    player_tick(player);
    const auto tick = static_cast<std::int32_t>(static_cast<std::uint64_t>(i) * 1000 / kRate);
    if (i >= kRate) {
      EXPECT_EQ(channel.output, sample(reference, cache, tick)) << "tick " << i;
      ++exact;
    }
  }
  EXPECT_EQ(exact, 7 * static_cast<int>(kRate));
}

// 10^4 switches: a random other show started, or a stop, every 1 to 150 ticks; every tick's
// position within the range, speed within the limit, speed change within the acceleration.
TEST(DevicePlayer, TenThousandSwitchesMidMotionStayWithinEveryLimit) {
  std::mt19937 rng(20261207);
  Figure f;
  set_up(f, rng, 4, 6);
  ASSERT_EQ(player_start(f.player, 0), kPlayerOk);
  std::vector<LimiterState> before(f.channels.size());
  std::size_t ticks = 0, over = 0;
  for (int switches = 0; switches < 10000; ++switches) {
    const int run = 1 + static_cast<int>(rng() % 150);
    for (int i = 0; i < run; ++i) {
      for (std::size_t c = 0; c < f.channels.size(); ++c) before[c] = f.channels[c].state;
      player_tick(f.player);
      ++ticks;
      for (std::size_t c = 0; c < f.channels.size(); ++c) {
        const ChannelLimits& l = f.limits[c]->limits;
        const LimiterState& s = f.channels[c].state;
        const bool ok = s.position >= l.low && s.position <= l.high && std::abs(s.velocity) <= l.speed &&
                        std::abs(s.velocity - before[c].velocity) <= l.accel && s.position - before[c].position == s.velocity;
        if (!ok && ++over <= 5)
          ADD_FAILURE() << "channel " << c << " at tick " << ticks << ": position " << s.position << " velocity " << s.velocity;
      }
    }
    if (rng() % 5 == 0) {
      player_stop(f.player);
    } else {
      ASSERT_EQ(player_start(f.player, static_cast<std::uint8_t>(rng() % f.shows.size())), kPlayerOk);
    }
  }
  EXPECT_EQ(over, 0u);
  EXPECT_GT(ticks, 500000u);
}

TEST(DevicePlayer, RefusesShowsAndLimitsItCannotPlay) {
  std::mt19937 rng(9);
  Figure f;
  set_up(f, rng, 2, 1);
  PlayerChannel one[1] = {};
  one[0].limits = f.channels[0].limits;
  Player p{};
  EXPECT_EQ(player_init(p, one, 1, f.shows.data(), 1, kRate), kPlayerBadChannels) << "a 2-channel show on 1 channel";
  std::vector<PlayerChannel> channels = f.channels;
  ChannelLimits stopped = f.limits[1]->limits;
  stopped.speed = 0;
  const StoredLimits no_speed(stopped);
  channels[1].limits = no_speed.bytes.data();
  EXPECT_EQ(player_init(p, channels.data(), 2, f.shows.data(), 1, kRate), kPlayerBadLimits);
  ChannelLimits unprepared = f.limits[1]->limits;
  unprepared.reach += 1;  // a stored reach the limiter would not compute: a damaged record
  const StoredLimits bad_reach(unprepared);
  channels[1].limits = bad_reach.bytes.data();
  EXPECT_EQ(player_init(p, channels.data(), 2, f.shows.data(), 1, kRate), kPlayerBadLimits);
  std::vector<std::uint8_t> damaged = f.images[0];
  damaged[0] = 'x';
  const PlayerShow bad[] = {{damaged.data(), static_cast<std::uint32_t>(damaged.size())}};
  EXPECT_EQ(player_init(p, f.channels.data(), 2, bad, 1, kRate), kPlayerBadShow);
  EXPECT_THROW(device_limits({-100, 100}, 200, 10, 10, 0, kRate), std::invalid_argument);
}

}  // namespace
}  // namespace avar::device

namespace avar::device {
namespace {

// braking_speed is the largest speed whose discrete stop (v, v - a, v - 2a, ... while positive)
// fits the distance: seeded distances and accelerations over many magnitudes.
TEST(DeviceLimiter, BrakingSpeedIsTheLargestWhoseStopFits) {
  const auto stop = [](std::int64_t v, std::int64_t a) {
    std::int64_t sum = 0;
    for (std::int64_t s = v; s > 0; s -= a) sum += s;
    return sum;
  };
  std::mt19937_64 rng(77);
  for (int i = 0; i < 20000; ++i) {
    const auto d = static_cast<std::int64_t>(rng() >> (30 + rng() % 34));  // positions: below 2^33
    const auto a = static_cast<std::int64_t>(1 + (rng() >> (30 + rng() % 34)));
    if (d / a > 200000) continue;  // the reference sum would take too long
    const std::int64_t v = braking_speed(d, a);
    ASSERT_LE(stop(v, a), d) << "d " << d << " a " << a << " v " << v;
    ASSERT_GT(stop(v + 1, a), d) << "d " << d << " a " << a << " v " << v;
  }
  EXPECT_EQ(braking_speed(0, 5), 0);
  EXPECT_EQ(braking_speed(-3, 5), 0);
}

}  // namespace
}  // namespace avar::device
