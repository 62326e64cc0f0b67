// The MIT drive set's real-time calls (encode_tick, take, replies_complete, settle,
// encode_release) allocate nothing. The one allocation-counting file of this test binary: it
// replaces the global operator new. Only the drive set's calls are counted; the simulated
// motors and the test bus allocate freely.
#include <gtest/gtest.h>

#include <vector>

#include "../support/allocation_counter.hpp"
#include "../support/direct_can_bus.hpp"
#include "avar/firmware_iface/mit_drives.hpp"
#include "avar/sim/sim_mit_motor.hpp"

namespace avar::sim {
namespace {

TEST(MitDrivesAllocation, TicksReleaseAndSilenceAllocateNothing) {
  SimMitMotorConfig a, b;
  a.id = 1;
  b.id = 2;
  SimMitMotor m1(a), m2(b);
  test::DirectCanBus bus({&m1, &m2});
  firmware_iface::MitDrivesConfig config;
  config.actuators.push_back({.channel = 0, .node = 1, .calibration = {-90, 90, -1.5, 1.5}});
  config.actuators.push_back({.channel = 1, .node = 2, .calibration = {-90, 90, -1.5, 1.5}});
  config.reply_budget_ticks = 2;
  firmware_iface::MitDrives drives(config);
  firmware_iface::CanOutbox out(drives.max_tick_frames());
  ASSERT_EQ(drives.start(bus), Status::ok);
  std::vector<double> frame{10.0, -10.0};
  std::vector<firmware_iface::CanFrame> replies;
  replies.reserve(8);

  long counted = 0;
  for (int i = 0; i < 20; ++i) {
    if (i == 10) m2.set_answering(false);  // silence and the lost fault on the same path
    if (i == 15) drives.release_channel(0);
    frame[0] = 10.0 + i;
    long before = testing::allocations.load();
    out.clear();
    drives.encode_tick(frame, out);
    counted += testing::allocations.load() - before;
    ASSERT_EQ(bus.send(out.frames()), Status::ok);
    replies.clear();
    firmware_iface::CanFrame f;
    while (bus.receive(&f, bus.now()) == Status::ok) replies.push_back(f);
    before = testing::allocations.load();
    for (const firmware_iface::CanFrame& r : replies) drives.take(r);
    (void)drives.replies_complete();
    (void)drives.settle();
    counted += testing::allocations.load() - before;
    bus.advance(std::chrono::milliseconds(5));
  }
  const long before = testing::allocations.load();
  out.clear();
  drives.encode_release(out);
  counted += testing::allocations.load() - before;
  EXPECT_EQ(counted, 0);
  EXPECT_EQ(out.size(), 2u);
}

}  // namespace
}  // namespace avar::sim
