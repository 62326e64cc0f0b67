// The supervisor alone: the fault latch, the fail-safe bookkeeping and the link watch, with no
// motion behind it.

#include "avar/control/supervisor.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "../support/recording_link.hpp"

namespace avar::control {
namespace {

/// Channels a, b, c, d on two links: a rests, b holds, c releases, d has no actuator.
rig::Rig four_channels() {
  rig::Rig r;
  for (const char* name : {"a", "b", "c", "d"}) r.channels.emplace_back().name = name;
  r.links.resize(2);
  const rig::Failsafe actions[] = {rig::Failsafe::rest, rig::Failsafe::hold, rig::Failsafe::release};
  for (std::size_t c = 0; c < 3; ++c) {
    rig::ActuatorSpec a;
    a.channel = rig::ChannelIndex{c};
    a.link = rig::LinkIndex{c == 2 ? 1u : 0u};
    a.failsafe = actions[c];
    r.actuators.push_back(a);
  }
  return r;
}

TEST(SupervisorUnit, TheFirstFaultStaysLatchedWithTheStateItInterruptedAndLaterOnesAreCounted) {
  const rig::Rig r = four_channels();
  Supervisor s(r, 2);
  s.enter(Phase::running);
  EXPECT_TRUE(s.latch(FaultCause::tracking_error, 1, 2.5, 3.0, Status::ok));
  EXPECT_FALSE(s.latch(FaultCause::estop, 0, 0, 3.1, Status::ok));
  EXPECT_EQ(s.phase(), Phase::faulted);
  EXPECT_EQ(s.latched_fault().cause, FaultCause::tracking_error);
  EXPECT_EQ(s.latched_fault().from, Phase::running);
  EXPECT_DOUBLE_EQ(s.latched_fault().value, 2.5);
  EXPECT_DOUBLE_EQ(s.latched_fault().time_s, 3.0);
  EXPECT_EQ(s.faults_seen(), 2u);
  EXPECT_TRUE(s.driving_failsafe());
  s.enter(Phase::running);  // motion resumes only after clear()
  EXPECT_EQ(s.phase(), Phase::faulted);
  s.enter(Phase::disabled);  // released at once: the fault stays latched
  EXPECT_EQ(s.phase(), Phase::disabled);
  EXPECT_EQ(s.latched_fault().cause, FaultCause::tracking_error);
}

TEST(SupervisorUnit, AFaultWhileIdleLatchesButDrivesNothing) {
  const rig::Rig r = four_channels();
  Supervisor s(r, 2);
  EXPECT_FALSE(s.latch(FaultCause::estop, 0, 0, 0.5, Status::ok));
  EXPECT_EQ(s.phase(), Phase::faulted);
  EXPECT_FALSE(s.drives());
  EXPECT_TRUE(s.clear());
  EXPECT_EQ(s.phase(), Phase::disabled);
  EXPECT_EQ(s.latched_fault().cause, FaultCause::none);
  EXPECT_FALSE(s.clear());
}

TEST(SupervisorUnit, FailsafeGoalRestsOrHoldsPerChannelAndReleaseGoesToTheRightLink) {
  const rig::Rig r = four_channels();
  Supervisor s(r, 2);
  const std::vector<double> rest{0, 0, 0, 0}, heading{1, 2, 3, 4};
  std::vector<double> goal(4);
  s.failsafe_goal(rest, heading, goal);
  // a rests; b holds; c releases (its command holds where it was heading); d has no actuator: rest.
  EXPECT_EQ(goal, (std::vector<double>{0, 2, 3, 0}));
  testing::RecordingLink first, second;
  firmware_iface::ActuatorLink* links[] = {&first, &second};
  s.release_failsafe(links);
  EXPECT_TRUE(first.released_channels.empty());
  EXPECT_EQ(second.released_channels, std::vector<std::size_t>{2});
}

TEST(SupervisorUnit, DeadLinksAreWatchedUntilCleared) {
  const rig::Rig r = four_channels();
  Supervisor s(r, 2);
  s.enter(Phase::running);
  s.link_died(0);
  EXPECT_TRUE(s.link_dead(0));
  EXPECT_TRUE(s.any_link_alive());
  s.link_died(1);
  EXPECT_FALSE(s.any_link_alive());
  ASSERT_TRUE(s.latch(FaultCause::link_failure, 1, 0, 1.0, Status::io_error));
  EXPECT_TRUE(s.clear());
  EXPECT_FALSE(s.link_dead(0));
  EXPECT_TRUE(s.any_link_alive());
}

}  // namespace
}  // namespace avar::control
