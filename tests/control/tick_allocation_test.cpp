// The real-time rule: once built, the tick allocates nothing. Counts every operator new in this
// test binary and asserts none happens across thousands of ticks through every phase, with the
// real Maestro link encoding into a transport.
#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"


#include "avar/control/controller.hpp"
#include "avar/firmware_iface/maestro_link.hpp"


namespace avar::control {
namespace {

class CountingTransport final : public firmware_iface::ByteTransport {
 public:
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    written_ += bytes.size();
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t>, std::chrono::milliseconds) noexcept override { return Status::timeout; }
  void discard_input() noexcept override {}
  std::uint64_t bytes_written() const noexcept override { return written_; }
  const std::string& name() const noexcept override { return name_; }

 private:
  std::uint64_t written_ = 0;
  std::string name_ = "counting";
};

TEST(TickAllocation, NoAllocationInAnyPhaseOfTheTick) {
  Rig rig;
  rig.name = "alloc";
  firmware_iface::MaestroLinkConfig link_config;
  link_config.channel_count = 12;
  for (int i = 0; i < 8; ++i) {
    const std::string name = "ch" + std::to_string(i);
    rig.channels.push_back({.name = name, .unit = "deg", .min = -45, .max = 45, .rest = 0, .max_velocity = 400, .max_acceleration = 4000, .max_jerk = 40000, .ramp_velocity = 60, .where = {}});
    // Two runs of consecutive device channels (0-3 and 6-9) exercise both packet kinds.
    const int device_channel = i < 4 ? i : i + 2;
    link_config.actuators.push_back({static_cast<std::size_t>(i), device_channel, {-45, 45, 1000, 2000, i % 2 == 1, 5}, {}, {}});
  }
  playback::Show show;
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
  CountingTransport transport;
  firmware_iface::MaestroLink link(transport, link_config);
  Controller controller(rig, show, {&link}, {.tick_period_s = 0.001});
  controller.begin(0.0, rig.rest_frame());

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

}  // namespace
}  // namespace avar::control
