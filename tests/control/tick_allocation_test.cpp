// The real-time rule: once built, the tick allocates nothing. Counts every operator new in this
// test binary and asserts none happens across thousands of ticks through every phase, with the
// real Maestro link encoding into a transport.
#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"


#include "avar/control/controller.hpp"
#include "avar/control/threaded_link.hpp"
#include "avar/firmware_iface/maestro_link.hpp"

#include <atomic>
#include <memory>


namespace avar::control {
namespace {

class CountingTransport final : public firmware_iface::ByteTransport {
 public:
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    written_.fetch_add(bytes.size(), std::memory_order_relaxed);
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t>, std::chrono::milliseconds) noexcept override { return Status::timeout; }
  void discard_input() noexcept override {}
  Status reopen() noexcept override { return Status::ok; }
  std::uint64_t bytes_written() const noexcept override { return written_.load(std::memory_order_relaxed); }
  const std::string& name() const noexcept override { return name_; }

 private:
  std::atomic<std::uint64_t> written_{0};
  std::string name_ = "counting";
};

struct Scene {
  Rig rig;
  playback::Show show;
  firmware_iface::MaestroLinkConfig link_config;
};

Scene scene() {
  Scene sc;
  Rig& rig = sc.rig;
  playback::Show& show = sc.show;
  firmware_iface::MaestroLinkConfig& link_config = sc.link_config;
  rig.name = "alloc";
  link_config.channel_count = 12;
  for (int i = 0; i < 8; ++i) {
    const std::string name = "ch" + std::to_string(i);
    rig.channels.push_back({.name = name, .unit = "deg", .min = -45, .max = 45, .rest = 0, .max_velocity = 400, .max_acceleration = 4000, .max_jerk = 40000, .ramp_velocity = 60, .tracking_tolerance = 0.5, .where = {}});
    // Two runs of consecutive device channels (0-3 and 6-9) exercise both packet kinds.
    const int device_channel = i < 4 ? i : i + 2;
    link_config.actuators.push_back({static_cast<std::size_t>(i), device_channel, {-45, 45, 1000, 2000, i % 2 == 1, 5}, {}, {}});
    ActuatorSpec spec;
    spec.channel = static_cast<std::size_t>(i);
    spec.failsafe = i % 3 == 0 ? Failsafe::release : (i % 3 == 1 ? Failsafe::hold : Failsafe::rest);
    rig.actuators.push_back(spec);
  }
  rig.links.emplace_back().name = "bus";
  show.name = "alloc";
  show.duration = 4;
  for (int i = 0; i < 8; ++i) {
    playback::RawCurve raw;
    for (int k = 0; k <= 40; ++k) {
      playback::RawKey key;
      key.time = k * 0.1;
      key.value = (k % 2 ? 40.0 : -40.0) * (i + 1) / 8.0;
      key.interpolation = static_cast<playback::Interpolation>(k % 3);
      key.left = playback::Handle{key.time - 0.03, key.value};
      key.right = playback::Handle{key.time + 0.03, key.value};
      raw.keys.push_back(key);
    }
    playback::Curve curve = playback::Curve::build(raw);
    show.tracks.push_back({"ch" + std::to_string(i), raw, std::move(curve), {}});
  }
  return sc;
}

TEST(TickAllocation, NoAllocationInAnyPhaseOfTheTick) {
  const Scene sc = scene();
  CountingTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  Controller controller(sc.rig, sc.show, {&link}, {.tick_period_s = 0.001});
  controller.begin(0.0, sc.rig.rest_frame());

  const long before = testing::allocations.load();
  int k = 0;
  bool stopped = false;
  for (; controller.active() && k < 100000; ++k) {
    if (!stopped && controller.show_time() > 3.0) {
      controller.request_stop(k * 0.001);
      stopped = true;
    }
    controller.tick(k * 0.001);
  }
  const long after = testing::allocations.load();
  EXPECT_TRUE(stopped);
  EXPECT_GT(k, 3000);
  EXPECT_GT(transport.bytes_written(), 0u);
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
}

// The same through the I/O thread and its mailbox, with feedback, a tracking fault and every
// fail-safe action: nothing allocates on either thread.
TEST(TickAllocation, NoAllocationThroughTheIoThreadAndTheFaultPath) {
  const Scene sc = scene();
  CountingTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  ThreadedLink threaded(link, sc.rig.channels.size(), 100000);
  Controller controller(sc.rig, sc.show, {&threaded}, {.tick_period_s = 0.001});
  controller.begin(0.0, sc.rig.rest_frame());
  std::vector<double> measured(sc.rig.channels.size(), 0.0);
  std::unique_ptr<bool[]> known(new bool[sc.rig.channels.size()]());

  const long before = testing::allocations.load();
  int k = 0;
  for (; controller.active() && k < 100000; ++k) {
    std::copy(controller.commanded().begin(), controller.commanded().end(), measured.begin());
    known[0] = true;
    if (controller.show_time() > 2.0) measured[0] += 1.0;  // beyond the tracking tolerance
    controller.feed_back(measured, std::span<const bool>(known.get(), sc.rig.channels.size()));
    controller.tick(k * 0.001);
  }
  const long after = testing::allocations.load();
  EXPECT_EQ(controller.latched_fault().cause, FaultCause::tracking_error);
  EXPECT_GT(k, 2000);
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
}

}  // namespace
}  // namespace avar::control
