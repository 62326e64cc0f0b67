// The I/O thread and its mailbox: frames arrive whole and newest-first, a stalled link never
// blocks the tick, and the watchdog turns silence into a fault. Run under ThreadSanitizer too.
#include "avar/control/threaded_link.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/frame_mailbox.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_wire.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

TEST(FrameMailbox, DeliversOnlyTheNewestFrameOnce) {
  FrameMailbox box(2);
  std::vector<double> out{-1, -1};
  EXPECT_FALSE(box.take(out));
  box.publish(std::vector<double>{1, 1});
  box.publish(std::vector<double>{2, 2});
  ASSERT_TRUE(box.take(out));
  EXPECT_EQ(out, (std::vector<double>{2, 2}));
  EXPECT_FALSE(box.take(out));
}

TEST(FrameMailbox, ReaderAlwaysSeesWholeFramesInOrderUnderContention) {
  constexpr int kFrames = 200000;
  FrameMailbox box(16);
  std::thread writer([&] {
    std::vector<double> frame(16);
    for (int k = 1; k <= kFrames; ++k) {
      std::fill(frame.begin(), frame.end(), static_cast<double>(k));
      box.publish(frame);
    }
  });
  std::vector<double> got(16, 0.0);
  double last = 0;
  while (last < kFrames) {
    if (!box.take(got)) continue;
    for (double v : got) ASSERT_EQ(v, got[0]) << "a torn frame";
    ASSERT_GT(got[0], last) << "an old frame after a newer one";
    last = got[0];
  }
  writer.join();
}

/// An ActuatorLink that can be made to stall (as a device that stops reading would stall a
/// write) and records what it was sent.
class StallableLink final : public firmware_iface::ActuatorLink {
 public:
  Status start() override { return Status::ok; }
  Status read_positions(std::span<double>, std::span<bool>) override { return Status::ok; }
  Status send(std::span<const double> frame) noexcept override {
    std::unique_lock lock(mutex_);
    sent_.emplace_back(frame.begin(), frame.end());
    cv_.notify_all();
    cv_.wait(lock, [&] { return !stalled_; });
    return Status::ok;
  }
  Status release() noexcept override {
    std::lock_guard lock(mutex_);
    ++releases_;
    return Status::ok;
  }
  void release_channel(std::size_t channel) noexcept override { released_channels.push_back(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return 0; }
  const std::string& describe() const noexcept override { return name_; }

  void stall(bool on) {
    std::lock_guard lock(mutex_);
    stalled_ = on;
    cv_.notify_all();
  }
  /// Waits until at least n frames were sent; returns the last one.
  std::vector<double> wait_sent(std::size_t n) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return sent_.size() >= n; });
    return sent_.back();
  }
  std::size_t sent_count() {
    std::lock_guard lock(mutex_);
    return sent_.size();
  }
  int releases() {
    std::lock_guard lock(mutex_);
    return releases_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::vector<double>> sent_;

 public:
  std::vector<std::size_t> released_channels;

 private:
  bool stalled_ = false;
  int releases_ = 0;
  std::string name_ = "stallable";
};

TEST(ThreadedLink, BringsTheInnerLinksTelemetryToTheTickThreadForItsChannelsOnly) {
  sim::SimDynamixelConfig bus;
  bus.servos.resize(2);
  bus.servos[1].id = 2;
  sim::SimDynamixel device(bus);
  sim::SimWire wire(device, 1'000'000);
  firmware_iface::DynamixelLinkConfig config;
  for (std::uint8_t id : {std::uint8_t{1}, std::uint8_t{2}}) {
    firmware_iface::DynamixelActuator a;
    a.channel = id;  // channels 1 and 2 of a 3-channel frame; channel 0 is another link's
    a.id = id;
    a.calibration = {-90, 90, 1024, 3072, false, 0};
    config.actuators.push_back(a);
  }
  firmware_iface::DynamixelLink inner(wire, config);
  ASSERT_EQ(inner.start(), Status::ok);
  ThreadedLink link(inner, 3, 1000);
  std::vector<firmware_iface::ChannelTelemetry> telemetry(3);
  telemetry[0].position = 123;  // another link's: must stay untouched
  telemetry[0].updates = 9;
  const std::vector<double> frame{0, 30, -30};
  // Enough exchanges (about 1 ms of simulated bus time each) for the servos to arrive.
  for (int i = 0; i < 50000 && !(telemetry[1].updates > 800 && telemetry[2].updates > 800); ++i) {
    const std::uint64_t done = link.completed_sends();
    ASSERT_EQ(link.send(frame), Status::ok);
    while (link.completed_sends() == done) std::this_thread::yield();  // the I/O thread's exchange
    link.read_telemetry(telemetry);
  }
  EXPECT_GT(telemetry[1].updates, 50u);
  EXPECT_GT(telemetry[2].updates, 50u);
  EXPECT_DOUBLE_EQ(telemetry[0].position, 123);
  EXPECT_EQ(telemetry[0].updates, 9u);
  EXPECT_NEAR(telemetry[1].position, 30, 1);
  EXPECT_NEAR(telemetry[2].position, -30, 1);
  EXPECT_GT(link.counters().replies, 100u);
}

TEST(ThreadedLink, SendsTheNewestFrameFromItsOwnThread) {
  StallableLink inner;
  ThreadedLink link(inner, 2, 50);
  EXPECT_EQ(link.send(std::vector<double>{1, 2}), Status::ok);
  EXPECT_EQ(inner.wait_sent(1), (std::vector<double>{1, 2}));
}

TEST(ThreadedLink, AStalledLinkNeverBlocksTheTickAndTheWatchdogFires) {
  StallableLink inner;
  ThreadedLink link(inner, 1, 10);
  inner.stall(true);
  ASSERT_EQ(link.send(std::vector<double>{0}), Status::ok);
  inner.wait_sent(1);  // the I/O thread is now stuck inside the inner send
  int ticks_until_timeout = 0;
  Status s = Status::ok;
  for (int k = 1; k <= 100 && s == Status::ok; ++k) {
    s = link.send(std::vector<double>{static_cast<double>(k)});  // returns at once every time
    ticks_until_timeout = k;
  }
  // The send that stalled was the first without completion; ten more are allowed, the next
  // (the eleventh in a row) times out.
  EXPECT_EQ(s, Status::timeout);
  EXPECT_EQ(ticks_until_timeout, 10);
  inner.stall(false);
  // Once unstalled, the newest frame goes out (the ones in between were dropped).
  EXPECT_EQ(inner.wait_sent(2), (std::vector<double>{10.0}));
}

TEST(ThreadedLink, ReleaseRunsOnTheIoThreadOnceAndStopsSending) {
  StallableLink inner;
  {
    ThreadedLink link(inner, 1, 10);
    EXPECT_EQ(link.send(std::vector<double>{1}), Status::ok);
    inner.wait_sent(1);
    EXPECT_EQ(link.release(), Status::ok);
    EXPECT_EQ(link.release(), Status::ok);
  }
  EXPECT_EQ(inner.releases(), 1);
  EXPECT_EQ(inner.sent_count(), 1u);
}

// End to end at the controller: one of two links goes silent mid-show; the tick never blocks,
// the watchdog reports it within its tick budget, and the other link eases to rest.
TEST(ThreadedLink, SilentLinkMidShowFaultsWithinTheWatchdogAndTheRestEasesToRest) {
  Rig rig;
  rig.name = "two links";
  for (const char* name : {"a", "b"})
    rig.channels.push_back({.name = name, .unit = "deg", .min = 0, .max = 30, .rest = 0, .max_velocity = 100,
                            .max_acceleration = 1000, .max_jerk = 20000, .ramp_velocity = 20, .where = {}});
  playback::Show show;
  show.name = "hold";
  show.duration = 4;
  for (const char* name : {"a", "b"}) {
    playback::RawCurve raw;
    playback::RawKey k0, k1;
    k0.time = 0, k0.value = 10, k1.time = 1, k1.value = 20;
    raw.keys = {k0, k1};
    playback::Curve curve = playback::Curve::build(raw);
    show.tracks.push_back({name, raw, std::move(curve), {}});
  }
  StallableLink healthy_inner, silent_inner;
  constexpr std::uint32_t kWatchdogTicks = 12;  // 0.12 s at 100 Hz
  ThreadedLink healthy(healthy_inner, 2, 1000), silent(silent_inner, 2, kWatchdogTicks);
  Controller c(rig, show, {&healthy, &silent}, {.tick_period_s = 0.01});
  c.begin(0, rig.rest_frame());
  const double dt = 0.01;
  int k = 0;
  for (; k < 150; ++k) {
    c.tick(k * dt);
    healthy_inner.wait_sent(static_cast<std::size_t>(k) + 1);  // keep the healthy link in step
    silent_inner.wait_sent(static_cast<std::size_t>(k) + 1);
  }
  // The last good send counts as completed only once the I/O thread has also brought back its
  // telemetry; a tick that runs before that (the I/O thread descheduled, as under TSan on a busy
  // machine) would start the watchdog later than the stall. Wait for it, so the bound below is
  // the watchdog's own.
  while (silent.completed_sends() < static_cast<std::uint64_t>(k)) std::this_thread::yield();
  silent_inner.stall(true);  // the device stops answering: its writes never complete
  const int silent_from = k;
  for (; c.active() && k < 2000; ++k) {
    c.tick(k * dt);
    healthy_inner.wait_sent(static_cast<std::size_t>(k) + 1);
  }
  EXPECT_EQ(c.latched_fault().cause, FaultCause::link_watchdog);
  EXPECT_EQ(c.latched_fault().index, 1u);
  EXPECT_EQ(c.latched_fault().status, Status::timeout);
  // Detected within the watchdog (plus the send that was already under way).
  EXPECT_LE(c.latched_fault().time_s - silent_from * dt, (kWatchdogTicks + 2) * dt + 1e-9);
  // The healthy link brought its channels to rest.
  const std::vector<double> last = healthy_inner.wait_sent(static_cast<std::size_t>(k));
  EXPECT_DOUBLE_EQ(last[0], 0.0);
  EXPECT_DOUBLE_EQ(last[1], 0.0);
  silent_inner.stall(false);
}

}  // namespace
}  // namespace avar::control
