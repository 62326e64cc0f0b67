// SimCanBus and SimCanTransport: arbitration, wire time and load figures, both timings, faults
// (error frames, bus-off, nodes dropping off), and the transport's clock and deadlines.
#include "avar/sim/sim_can_bus.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "../support/can_responder_node.hpp"
#include "avar/sim/sim_can_transport.hpp"

namespace avar::sim {
namespace {

using firmware_iface::can_data_frame;
using firmware_iface::can_remote_frame;
using firmware_iface::CanFrame;
using namespace std::chrono_literals;
using test::CanResponderNode;

CanFrame bus_frame(std::uint32_t id, std::size_t bytes = 8, bool extended = false) {
  return can_data_frame(id, std::vector<std::uint8_t>(bytes, 0x11), extended);
}

TEST(SimCanBus, SixteenEightByteFramesAtOneMegabitTake2160BitsAnd2160Microseconds) {
  CanResponderNode listener{0x700};
  SimCanBus bus({}, {&listener});
  SimCanTransport t(bus);
  std::vector<CanFrame> frames;
  for (std::uint32_t i = 0; i < 16; ++i) frames.push_back(bus_frame(0x200 + i));
  ASSERT_EQ(t.send(frames), Status::ok);
  EXPECT_NEAR(t.now_s(), 2.16e-3, 1e-12);
  const SimCanBusStatistics s = t.statistics();
  EXPECT_EQ(s.frames, 16u);
  EXPECT_EQ(s.bits, 2160u);
  EXPECT_NEAR(s.busy_s, 2.16e-3, 1e-12);
  EXPECT_NEAR(s.elapsed_s, 2.16e-3, 1e-12);
  EXPECT_NEAR(s.load(), 1.0, 1e-9);
  EXPECT_EQ(listener.heard.size(), 16u);
  EXPECT_EQ(t.now(), std::chrono::nanoseconds(2'160'000));
  // Idle time lowers the load: the same 2.16 ms of traffic in 4.32 ms is 50 %.
  CanFrame f;
  EXPECT_EQ(t.receive(&f, t.now() + 2160us), Status::timeout);
  EXPECT_NEAR(t.statistics().load(), 0.5, 1e-9);
}

TEST(SimCanBus, TheLowestIdentifierWinsArbitrationAmongEverythingPending) {
  CanResponderNode a{0x7F0}, b{0x7F1};
  SimCanBus bus({}, {&a, &b});
  a.queue(bus_frame(0x300));
  a.queue(bus_frame(0x050));  // behind a's 0x300: a node offers its oldest frame only
  b.queue(bus_frame(0x100));
  b.queue(bus_frame(0x020, 0, true));  // extended 0x20: base id 0 beats everything standard
  ASSERT_EQ(bus.host_send(bus_frame(0x200)), Status::ok);
  ASSERT_TRUE(bus.run_until(0.01));
  std::vector<std::uint32_t> order;
  CanFrame f;
  while (bus.host_receive(&f)) order.push_back(f.id);
  // b's 0x100 beats a's 0x300 and the host's 0x200; then b's extended 0x20 (base 0); then the
  // host's 0x200 beats a's 0x300; then a's 0x050. The host hears everything but its own frame.
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0x100, 0x020, 0x300, 0x050}));
  ASSERT_EQ(a.heard.size(), 3u);  // b's two and the host's
  EXPECT_EQ(a.heard[2].id, 0x200u);
}

TEST(SimCanBus, ArbitrationFieldOrdersFormatAndRemoteFrames) {
  CanResponderNode a{0x7F0}, b{0x7F1}, c{0x7F2};
  SimCanBus bus({}, {&a, &b, &c});
  a.queue(can_remote_frame(0x123, 2));       // standard remote
  b.queue(bus_frame(0x123 << 18, 1, true));  // extended, same base id
  c.queue(bus_frame(0x123, 1));              // standard data: wins
  ASSERT_TRUE(bus.run_until(0.01));
  CanFrame f;
  ASSERT_TRUE(bus.host_receive(&f));
  EXPECT_FALSE(f.rtr);
  EXPECT_FALSE(f.extended);
  ASSERT_TRUE(bus.host_receive(&f));
  EXPECT_TRUE(f.rtr);  // a standard remote frame still beats an extended one of the same base id
  ASSERT_TRUE(bus.host_receive(&f));
  EXPECT_TRUE(f.extended);
}

TEST(SimCanBus, TheHostsFrameGoesFirstOnAnExactTie) {
  CanResponderNode node{0x7F0};
  SimCanBus bus({}, {&node});
  node.queue(bus_frame(0x123, 1));
  ASSERT_EQ(bus.host_send(bus_frame(0x123, 2)), Status::ok);
  ASSERT_TRUE(bus.run_until(bus.now_s() + 1e-3));
  ASSERT_EQ(node.heard.size(), 1u);
  EXPECT_EQ(node.heard[0].dlc, 2);  // the host's went first
  EXPECT_EQ(bus.statistics().host_frames, 1u);
}

TEST(SimCanBus, RepliesComeAfterTheirRequestsWireTimeAndTheNodesDelay) {
  CanResponderNode node{0x123, 0.5e-3};
  SimCanBus bus({}, {&node});
  SimCanTransport t(bus);
  const CanFrame request = bus_frame(0x123);
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
  EXPECT_NEAR(t.now_s(), 135e-6, 1e-12);
  CanFrame reply;
  ASSERT_EQ(t.receive(&reply, t.now() + 10ms), Status::ok);
  EXPECT_EQ(reply.id, 0x124u);
  // Request 135 µs, the node's 500 µs (released at the next 100 µs idle step), reply 135 µs.
  EXPECT_GE(t.now_s(), 135e-6 + 0.5e-3 + 135e-6 - 1e-12);
  EXPECT_LE(t.now_s(), 135e-6 + 0.6e-3 + 135e-6 + 1e-12);
  EXPECT_EQ(reply.timestamp, t.now());
  EXPECT_NEAR(node.now_s(), t.now_s(), 1e-12);  // the node's time moved with the bus
}

TEST(SimCanBus, ReceiveEndsAtTheDeadlineWhenNothingComes) {
  CanResponderNode node{0x123};
  SimCanBus bus({}, {&node});
  SimCanTransport t(bus);
  const auto deadline = t.now() + 3ms;
  CanFrame f;
  EXPECT_EQ(t.receive(&f, deadline), Status::timeout);
  EXPECT_EQ(t.now(), deadline);
  EXPECT_NEAR(node.now_s(), 3e-3, 1e-12);
  EXPECT_EQ(t.receive(&f, deadline - 1ms), Status::timeout);  // a passed deadline: no time moves
  EXPECT_EQ(t.now(), deadline);
}

TEST(SimCanBus, InstantTimingDeliversAtOnceAndCountsWireTimeForLoad) {
  CanResponderNode node{0x123};
  SimCanBusConfig config;
  config.timing = SimCanTiming::instant;
  SimCanBus bus(config, {&node});
  for (int i = 0; i < 16; ++i) ASSERT_EQ(bus.host_send(bus_frame(0x123)), Status::ok);
  ASSERT_TRUE(bus.run_until(bus.now_s()));
  EXPECT_EQ(bus.now_s(), 0.0);
  EXPECT_EQ(bus.host_pending(), 16u);  // every reply already there
  EXPECT_EQ(bus.statistics().bits, 2u * 2160u);
  EXPECT_NEAR(bus.statistics().busy_s, 4.32e-3, 1e-12);
  bus.run_until(0.01);  // time moves only here
  EXPECT_NEAR(bus.now_s(), 0.01, 1e-12);
  EXPECT_NEAR(bus.statistics().load(), 0.432, 1e-9);
  bus.reset_statistics();
  EXPECT_EQ(bus.statistics().frames, 0u);
  EXPECT_EQ(bus.statistics().elapsed_s, 0.0);
}

TEST(SimCanBus, InjectedErrorFramesReachTheHostWithTheirClass) {
  SimCanBus bus;
  SimCanTransport t(bus);
  bus.inject_error(firmware_iface::kCanErrorPassive | firmware_iface::kCanErrorAck);
  CanFrame f;
  ASSERT_EQ(t.receive(&f, t.now()), Status::ok);
  EXPECT_TRUE(f.error);
  EXPECT_EQ(f.id, firmware_iface::kCanErrorPassive | firmware_iface::kCanErrorAck);
  EXPECT_EQ(t.counters().error_frames, 1u);
  EXPECT_EQ(t.counters().frames_received, 0u);
}

TEST(SimCanBus, BusOffSilencesTheHostUntilReopen) {
  CanResponderNode node{0x123};
  SimCanBus bus({}, {&node});
  SimCanTransport t(bus);
  ASSERT_EQ(bus.host_send(bus_frame(0x123)), Status::ok);  // queued, lost with the bus-off
  bus.inject_bus_off();
  CanFrame f;
  ASSERT_EQ(t.receive(&f, t.now() + 1ms), Status::ok);
  EXPECT_TRUE(f.error);
  EXPECT_EQ(f.id, firmware_iface::kCanErrorBusOff);
  EXPECT_EQ(t.counters().bus_off, 1u);
  const CanFrame request = bus_frame(0x123);
  EXPECT_EQ(t.send(std::span(&request, 1)), Status::io_error);
  node.queue(bus_frame(0x555));  // a bus-off controller hears nothing
  EXPECT_EQ(t.receive(&f, t.now() + 1ms), Status::timeout);
  EXPECT_TRUE(node.heard.empty());
  ASSERT_EQ(t.reopen(), Status::ok);
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
  ASSERT_EQ(t.receive(&f, t.now() + 1ms), Status::ok);
  EXPECT_EQ(f.id, 0x124u);
}

TEST(SimCanBus, ADetachedNodeHearsAndSaysNothingAndLosesWhatItQueued) {
  CanResponderNode node{0x123};
  SimCanBus bus({}, {&node});
  SimCanTransport t(bus);
  node.queue(bus_frame(0x300));
  bus.set_attached(node, false);
  EXPECT_FALSE(bus.attached(node));
  const CanFrame request = bus_frame(0x123);
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);  // nobody acknowledges; the simulator does not model that
  CanFrame f;
  EXPECT_EQ(t.receive(&f, t.now() + 2ms), Status::timeout);
  EXPECT_TRUE(node.heard.empty());
  EXPECT_EQ(node.queued(), 0u);
  EXPECT_NEAR(node.now_s(), t.now_s(), 1e-12);  // its own time still runs
  bus.set_attached(node, true);
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
  ASSERT_EQ(t.receive(&f, t.now() + 2ms), Status::ok);
  EXPECT_EQ(f.id, 0x124u);
}

TEST(SimCanBus, SendTimesOutWhenHigherPriorityTrafficNeverStops) {
  /// A node that always has a frame on id 0 to send.
  struct Babbler final : CanNode {
    void receive(const CanFrame&) override {}
    bool peek_transmit(CanFrame* f) const override {
      *f = can_data_frame(0, std::vector<std::uint8_t>(8));
      return true;
    }
    void pop_transmit() override {}
    void advance(double) override {}
  } babbler;
  SimCanBus bus({}, {&babbler});
  SimCanTransport t(bus, "babbled bus", 0.005);
  const CanFrame request = bus_frame(0x123);
  EXPECT_EQ(t.send(std::span(&request, 1)), Status::timeout);
  EXPECT_GE(t.now_s(), 0.005);
  EXPECT_LT(t.now_s(), 0.006);
  EXPECT_NEAR(t.statistics().load(), 1.0, 0.03);
}

TEST(SimCanBus, InvalidFramesAreRefused) {
  SimCanBus bus;
  SimCanTransport t(bus);
  const CanFrame bad = can_data_frame(0x800, std::vector<std::uint8_t>{});
  EXPECT_EQ(t.send(std::span(&bad, 1)), Status::out_of_range);
  EXPECT_EQ(bus.host_send(bad), Status::out_of_range);
  EXPECT_EQ(t.statistics().frames, 0u);
  EXPECT_EQ(t.bitrate(), 1'000'000);
  EXPECT_EQ(t.name(), "simulated CAN bus");
}

}  // namespace
}  // namespace avar::sim
