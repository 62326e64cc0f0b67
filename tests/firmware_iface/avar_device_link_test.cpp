// The avar-device streaming link against the simulated device (the device's own player built for
// the host) over a simulated 115200-baud wire: the hello, the knots' cadence and size, a motion
// played on the device `lead` later within a few output units, positions read back, releases,
// and a device that cannot hold the lead refused with the reason.
#include "avar/firmware_iface/avar_device_link.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "avar/device/show_export.hpp"
#include "avar/sim/sim_avar_device.hpp"
#include "avar/sim/sim_wire.hpp"

namespace avar::firmware_iface {
namespace stream_tests {
namespace {

namespace wire = avar_device;
using std::chrono::microseconds;

constexpr double kTickS = 0.01;  // the loop at 100 Hz

sim::SimAvarDeviceConfig device_config(int channels, std::uint8_t knots = 16, double speed = 400, double accel = 8000) {
  sim::SimAvarDeviceConfig config;
  config.rate_hz = 200;
  config.knot_capacity = knots;
  config.watchdog_ms = 500;
  for (int c = 0; c < channels; ++c) {
    sim::SimAvarDeviceChannel ch;
    // -90..90 degrees, rest 0, 400 deg/s, 8000 deg/s^2 (the host's limits too).
    ch.limits = device::device_limits({-90, 90}, 0, speed, accel, 0, config.rate_hz);
    config.channels.push_back(ch);
  }
  return config;
}

AvarDeviceLinkConfig link_config(int channels) {
  AvarDeviceLinkConfig config;
  config.tick = microseconds(10000);
  config.knot_every = 5;
  config.lead = microseconds(150000);
  for (int c = 0; c < channels; ++c) {
    AvarDeviceActuator a;
    a.channel = static_cast<std::size_t>(c);
    a.device_channel = channels - 1 - c;  // the device's order is not the rig's
    a.calibration = {-90, 90, 0, 65535, false, 0};
    config.actuators.push_back(a);
  }
  return config;
}

double to_output(double degrees) { return (degrees + 90) / 180 * 65535; }

struct Rig {
  sim::SimAvarDevice device;
  sim::SimWire wire;
  AvarDeviceLink link;
  explicit Rig(int channels, std::uint8_t knots = 16, AvarDeviceLinkConfig config = {})
      : device(device_config(channels, knots, 20000, 1e7)),
        wire(device, 115200),
        link(wire, config.actuators.empty() ? link_config(channels) : config) {}
  /// One loop tick: the frame sent (the wire moves the device's time by the bytes' time), then
  /// the device's time moves on to the end of the tick: the device's clock runs as the loop's.
  Status tick(const std::vector<double>& frame) {
    const double before = wire.now_s();
    const Status s = link.send(frame);
    device.advance(kTickS - (wire.now_s() - before));
    return s;
  }
};

TEST(AvarDeviceLink, HelloReadsTheDevicesStatus) {
  Rig rig(3);
  ASSERT_EQ(rig.link.start(), Status::ok) << rig.link.start_problem();
  EXPECT_EQ(rig.link.device_status().channel_count, 3);
  EXPECT_EQ(rig.link.device_status().rate_hz, 200);
  EXPECT_EQ(rig.link.device_status().state, wire::kResting);
  EXPECT_NE(rig.link.describe().find("device at 200 Hz"), std::string::npos) << rig.link.describe();
}

TEST(AvarDeviceLink, RefusesADeviceThatDoesNotMatch) {
  sim::SimAvarDevice device(device_config(2));
  sim::SimWire wire(device, 115200);
  AvarDeviceLink link(wire, link_config(3));
  EXPECT_EQ(link.start(), Status::bad_data);
  EXPECT_NE(link.start_problem().find("the device drives 2 channels, the rig gives this link 3"), std::string::npos)
      << link.start_problem();

  Rig small(2, 4);  // 150 ms of lead at a knot per 50 ms needs 5
  EXPECT_EQ(small.link.start(), Status::bad_data);
  EXPECT_NE(small.link.start_problem().find("holds 4 knots ahead"), std::string::npos) << small.link.start_problem();

  Rig failed(2);
  failed.device.fail();
  EXPECT_EQ(failed.link.start(), Status::bad_data);
  EXPECT_NE(failed.link.start_problem().find("a servo board that does not answer"), std::string::npos)
      << failed.link.start_problem();

  AvarDeviceLinkConfig short_lead = link_config(1);
  short_lead.lead = microseconds(100000);
  EXPECT_THROW(AvarDeviceLink(wire, short_lead), std::invalid_argument) << "less than two knots and a tick";
  AvarDeviceLinkConfig twice = link_config(2);
  twice.actuators[1].device_channel = twice.actuators[0].device_channel;
  EXPECT_THROW(AvarDeviceLink(wire, twice), std::invalid_argument);
}

TEST(AvarDeviceLink, SendsAKnotAndTheClockEveryKnotSpacingAndNothingBetween) {
  Rig rig(4);
  ASSERT_EQ(rig.link.start(), Status::ok);
  std::vector<std::size_t> sizes;
  for (int t = 0; t < 12; ++t) {
    ASSERT_EQ(rig.tick({0, 0, 0, 0}), Status::ok);
    sizes.push_back(rig.link.last_send_size());
  }
  const std::size_t knot = 9 + (wire::kOverhead + 5 + 4 * 4);  // kTime + kKnots
  EXPECT_EQ(sizes, (std::vector<std::size_t>{0, knot, 0, 0, 0, 0, knot, 0, 0, 0, 0, knot}));
}

// A motion within the limits, commanded at 100 Hz: the device plays it 150 ms later (at each of its
// own ticks, on avar's clock) within 2 output units of 65535 (its cubic between knots 50 ms apart).
TEST(AvarDeviceLink, TheDevicePlaysTheMotionLeadLaterWithinTwoUnits) {
  Rig rig(2);
  ASSERT_EQ(rig.link.start(), Status::ok);
  auto command = [](int c, double t) { return 40 * std::sin(2 * M_PI * 0.5 * t + c) * std::min(1.0, t / 2); };
  double worst = 0;
  const double lead = 0.15;
  for (int tick = 0; tick < 800; ++tick) {
    const double t = tick * kTickS;
    ASSERT_EQ(rig.tick({command(0, t), command(1, t)}), Status::ok);
    // The stream time of the device's last control tick (its outputs change at its own rate).
    const std::uint32_t last_tick_us = static_cast<std::uint32_t>((rig.device.ticks() - 1) * 5000) + rig.device.player().offset;
    const double device_t = static_cast<std::int32_t>(last_tick_us) / 1e6;
    if (device_t > 2.5) {  // past the fade-in's corner at 2 s
      for (int c = 0; c < 2; ++c) {
        // Channel c is the device's output 1 - c.
        const double expected = to_output(command(c, device_t - lead));
        worst = std::max(worst, std::abs(rig.device.output(static_cast<std::size_t>(1 - c)) - expected));
      }
    }
  }
  EXPECT_EQ(rig.device.player().underruns, 0u);
  EXPECT_EQ(rig.device.player().parser.bad_frames, 0u);
  EXPECT_LE(worst, 2.0) << "output units of 65535 (2 is 0.0055 degrees)";
  const LinkCounters k = rig.link.counters();
  EXPECT_GE(k.exchanges, 160u) << "a write every fifth tick";
  EXPECT_LE(k.exchanges, 162u) << "and one more at the fade-in's corner at 2 s";
  EXPECT_LT(static_cast<double>(k.bytes_sent) / 8.0, 0.05 * 11520) << "bytes per second against the wire's 11,520";
}

// A blink (a lid closing and opening in 80 ms) is more than the cubic between knots 50 ms apart
// can follow: knots come sooner there, and the device follows it four times closer than with a
// knot every 50 ms whatever the motion.
TEST(AvarDeviceLink, KnotsComeSoonerWhereTheMotionTurnsFast) {
  auto command = [](double t) {
    const double u = (t - 1.0) / 0.08;  // a triangle from 60 down to -60 and back, 1.00 to 1.16 s
    return u < 0 || u > 2 ? 60.0 : 60.0 - 120.0 * (u < 1 ? u : 2 - u);
  };
  struct Outcome {
    std::size_t writes = 0;
    double worst = 0;
  };
  auto play = [&](double tolerance) {
    AvarDeviceLinkConfig config = link_config(1);
    config.fit_tolerance = tolerance;
    Rig rig(1, 16, config);
    EXPECT_EQ(rig.link.start(), Status::ok);
    Outcome out;
    for (int tick = 0; tick < 250; ++tick) {
      EXPECT_EQ(rig.tick({command(tick * kTickS)}), Status::ok);
      if (rig.link.last_send_size() > 0) ++out.writes;
      const std::uint32_t last_tick_us = static_cast<std::uint32_t>((rig.device.ticks() - 1) * 5000) + rig.device.player().offset;
      const double played = static_cast<std::int32_t>(last_tick_us) / 1e6 - 0.15;  // the host time it plays
      if (played > 0.5) out.worst = std::max(out.worst, std::abs(rig.device.output(0) - to_output(command(played))));
    }
    return out;
  };
  const Outcome fixed = play(1e9), fitted = play(16);
  EXPECT_EQ(fixed.writes, 50u);
  EXPECT_GT(fitted.writes, fixed.writes) << "knots sooner in the blink";
  EXPECT_LT(fitted.writes, fixed.writes + 12) << "and only there";
  EXPECT_LT(fitted.worst, fixed.worst / 4) << "output units: " << fitted.worst << " against " << fixed.worst;
}

TEST(AvarDeviceLink, ReadsPositionsAndReleases) {
  Rig rig(2);
  ASSERT_EQ(rig.link.start(), Status::ok);
  for (int tick = 0; tick < 100; ++tick) ASSERT_EQ(rig.tick({30, -20}), Status::ok);
  std::vector<double> frame(2, 0);
  bool known[2] = {false, false};
  ASSERT_EQ(rig.link.read_positions(frame, std::span<bool>(known, 2)), Status::ok);
  EXPECT_TRUE(known[0] && known[1]);
  EXPECT_NEAR(frame[0], 30, 0.01);
  EXPECT_NEAR(frame[1], -20, 0.01);

  rig.link.release_channel(1);  // the device's output 0
  ASSERT_EQ(rig.tick({30, -20}), Status::ok);
  EXPECT_TRUE(rig.device.player().channels[0].released);
  EXPECT_FALSE(rig.device.player().channels[1].released);
  EXPECT_EQ(rig.device.pulse_us(0), 0) << "a released output sends no pulse";
  ASSERT_EQ(rig.link.release(), Status::ok);
  rig.device.advance(kTickS);
  EXPECT_EQ(rig.device.player().state, wire::kReleased);
  EXPECT_EQ(rig.device.pulse_us(1), 0);
}

TEST(AvarDeviceLink, ASilentLinkLetsTheDeviceEaseToRestByItself) {
  Rig rig(1);
  ASSERT_EQ(rig.link.start(), Status::ok);
  for (int tick = 0; tick < 100; ++tick) ASSERT_EQ(rig.tick({60}), Status::ok);
  EXPECT_EQ(rig.device.player().state, wire::kStreaming);
  rig.device.advance(0.7);  // the host went away: past the device's 500 ms watchdog
  EXPECT_NE(rig.device.player().state, wire::kStreaming);
  rig.device.advance(2.0);
  EXPECT_EQ(rig.device.player().state, wire::kResting);
  EXPECT_NEAR(rig.device.output(0), to_output(0), 1);
}

}  // namespace
}  // namespace stream_tests
}  // namespace avar::firmware_iface
