// The simulated GPIO chip: levels and logical values as libgpiod gives them (active-low inverts,
// bias sets an undriven input), edges queued for waiters, errors that name the chip and the
// line, and the outside of the lines driven from another thread while a waiter waits.

#include "avar/sim/sim_gpio_chip.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace avar::sim {
namespace {

using firmware_iface::GpioBias;
using firmware_iface::GpioEdge;
using namespace std::chrono_literals;

bool simgpio_get(SimGpioChip& chip, unsigned line) {
  bool v = false;
  EXPECT_EQ(chip.get(line, v), Status::ok);
  return v;
}

TEST(SimGpioChip, OutputsDriveTheirLevelAndActiveLowInverts) {
  SimGpioChip chip;
  chip.request_output({17, false, false});
  chip.request_output({18, true, false});  // active-low, off: the line is high
  EXPECT_FALSE(chip.level(17));
  EXPECT_TRUE(chip.level(18));
  ASSERT_EQ(chip.set(17, true), Status::ok);
  ASSERT_EQ(chip.set(18, true), Status::ok);
  EXPECT_TRUE(chip.level(17));
  EXPECT_FALSE(chip.level(18));
  EXPECT_TRUE(simgpio_get(chip, 18));  // an output reads back its logical value
  EXPECT_EQ(chip.output_changes(17), 1u);
  ASSERT_EQ(chip.set(17, true), Status::ok);
  EXPECT_EQ(chip.output_changes(17), 1u);  // no change, no count
  chip.set_level(17, false);               // the outside cannot override a driven line
  EXPECT_TRUE(chip.level(17));
}

TEST(SimGpioChip, InputsReadTheOutsideOrTheirBias) {
  SimGpioChip chip;
  chip.request_input({4, true, GpioBias::pull_up, false});
  chip.request_input({5, false, GpioBias::pull_down, false});
  EXPECT_FALSE(simgpio_get(chip, 4));  // pulled up, active-low: inactive
  EXPECT_FALSE(simgpio_get(chip, 5));
  chip.set_level(4, false);  // a switch closes to ground
  chip.set_level(5, true);
  EXPECT_TRUE(simgpio_get(chip, 4));
  EXPECT_TRUE(simgpio_get(chip, 5));
  chip.float_line(4);
  EXPECT_FALSE(simgpio_get(chip, 4));
  EXPECT_EQ(chip.set(4, true), Status::out_of_range);  // an input is not driven
  bool v = false;
  EXPECT_EQ(chip.get(9, v), Status::out_of_range);  // not requested
}

TEST(SimGpioChip, EdgesOfLogicalChangesAreQueuedOldestFirst) {
  SimGpioChip chip;
  chip.request_input({4, true, GpioBias::pull_up, true});
  chip.request_input({6, false, GpioBias::as_is, false});  // no events asked
  chip.set_level(4, false);
  chip.set_level(4, false);  // no change: no edge
  chip.set_level(6, true);
  chip.set_level(4, true);
  GpioEdge edges[8];
  std::size_t n = 0;
  ASSERT_EQ(chip.wait_edges(0ns, edges, n), Status::ok);
  ASSERT_EQ(n, 2u);
  EXPECT_EQ(edges[0].line, 4u);
  EXPECT_TRUE(edges[0].rising);  // low on an active-low line: logical 1
  EXPECT_FALSE(edges[1].rising);
  EXPECT_LE(edges[0].time_ns, edges[1].time_ns);
  ASSERT_EQ(chip.wait_edges(1ms, edges, n), Status::ok);
  EXPECT_EQ(n, 0u);  // timed out
}

TEST(SimGpioChip, ABoundedQueueDropsTheOldestEdges) {
  SimGpioChip chip;
  chip.request_input({1, false, GpioBias::as_is, true});
  for (std::size_t i = 0; i < SimGpioChip::kEdgeQueue + 10; ++i) chip.set_level(1, i % 2 == 0);
  EXPECT_EQ(chip.edges_dropped(), 10u);
}

TEST(SimGpioChip, RequestErrorsNameTheChipAndTheLine) {
  SimGpioChip chip("props", 8);
  chip.request_output({3, false, false});
  try {
    chip.request_input({3, false, GpioBias::as_is, true});
    FAIL() << "line 3 was requested twice";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "simulated GPIO chip 'props': cannot request line 3 as an input: it is in use (requested twice)");
  }
  try {
    chip.request_output({8, false, false});
    FAIL() << "line 8 does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "simulated GPIO chip 'props' has 8 lines (0 to 7); line 8 does not exist");
  }
  chip.release(3);
  EXPECT_FALSE(chip.is_requested(3));
  chip.request_input({3, false, GpioBias::as_is, true});  // free again
  EXPECT_FALSE(chip.is_output(3));
}

TEST(SimGpioChip, AnotherThreadPressesWhileAWaiterWaits) {
  SimGpioChip chip;
  chip.request_input({2, false, GpioBias::as_is, true});
  chip.request_output({3, false, false});
  constexpr int kToggles = 200;
  std::atomic<bool> done{false};
  std::thread presser([&] {
    for (int i = 0; i < kToggles; ++i) {
      chip.set_level(2, i % 2 == 0);
      (void)chip.set(3, i % 2 == 0);  // and the loop side sets an output meanwhile
    }
    done.store(true);
  });
  std::size_t seen = 0;
  GpioEdge edges[16];
  while (!done.load() || seen < kToggles) {
    std::size_t n = 0;
    ASSERT_EQ(chip.wait_edges(50ms, edges, n), Status::ok);
    if (n == 0 && done.load()) break;
    seen += n;
  }
  presser.join();
  EXPECT_EQ(seen, static_cast<std::size_t>(kToggles));
  EXPECT_EQ(chip.edges_dropped(), 0u);
}

}  // namespace
}  // namespace avar::sim
