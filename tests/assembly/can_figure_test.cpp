// CAN figures end to end through the library: the example rigs load, assemble into the real
// SLCAN driver against simulated adapters and drives on pseudo-terminals, play on the stepped
// clock, and every drive fault mid-show ends in the fail-safe with the drive and cause named.

#include <gtest/gtest.h>

#include <atomic>
#include <functional>

#include "avar/assembly/figure_links.hpp"
#include "avar/assembly/simulated_can_bus.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/sim/sim_can_bus.hpp"
#include "avar/sim/sim_cia402_drive.hpp"
#include "avar/sim/sim_odrive_axis.hpp"
#include "../support/stepped_figure_run.hpp"

namespace avar {
namespace {

/// Runs `inject` on the simulated bus once, after tick `at`.
class CanFaultAt final : public control::TickObserver {
 public:
  CanFaultAt(assembly::FigureLinks& figure, std::uint64_t at, std::function<void(assembly::SimulatedCanBus&)> inject)
      : figure_(figure), at_(at), inject_(std::move(inject)) {}
  void after_tick(std::uint64_t tick, double, double, double, control::Controller&) override {
    if (tick != at_ || !inject_) return;
    figure_.with_simulated(0, [&](sim::ByteDevice& d) { inject_(dynamic_cast<assembly::SimulatedCanBus&>(d)); });
  }

 private:
  assembly::FigureLinks& figure_;
  std::uint64_t at_;
  std::function<void(assembly::SimulatedCanBus&)> inject_;
};

struct CanRun {
  control::Fault fault;
  std::uint64_t ticks = 0;
  std::string problem;
};

CanRun play_can(const char* rig_file, const char* show_file, std::uint64_t at,
                std::function<void(assembly::SimulatedCanBus&)> inject) {
  const rig::Rig rig = config::load_rig_file(std::string(AVAR_SOURCE_DIR "/examples/rigs/") + rig_file);
  const playback::Show show = config::load_show_file(std::string(AVAR_SOURCE_DIR "/examples/shows/") + show_file);
  assembly::FigureLinks figure(rig, {});
  for (firmware_iface::ActuatorLink* link : figure.links()) {
    const Status s = link->start();
    EXPECT_EQ(s, Status::ok) << link->start_problem();
    if (s != Status::ok) return {};
  }
  testing::SteppedFigureRun play(rig, show, figure);
  CanFaultAt observer(figure, at, std::move(inject));
  const control::RunResult result = play.run(observer);
  CanRun out;
  out.fault = play.controller.latched_fault();
  out.ticks = result.ticks;
  out.problem = figure.channel_problem(out.fault.index);
  return out;
}

TEST(CanFigure, OdriveArmPlaysWholeWithoutAFault) {
  const CanRun r = play_can("odrive-arm.yaml", "odrive-arm.yaml", 0, {});
  EXPECT_EQ(r.fault.cause, control::FaultCause::none) << r.problem;
  EXPECT_GT(r.ticks, 1000u);
}

TEST(CanFigure, Cia402TurntablePlaysWholeWithoutAFault) {
  const CanRun r = play_can("cia402-turntable.yaml", "turntable-tour.yaml", 0, {});
  EXPECT_EQ(r.fault.cause, control::FaultCause::none) << r.problem;
  EXPECT_GT(r.ticks, 1200u);
}

TEST(CanFigure, AnOdriveThatDropsOffTheBusIsLostWithinTheHeartbeatBudget) {
  // The shoulder (node 2) leaves the bus at tick 300; the budget is 300 ms = 30 ticks.
  const CanRun r = play_can("odrive-arm.yaml", "odrive-arm.yaml", 300,
                            [](assembly::SimulatedCanBus& bus) { bus.adapter().bus().set_attached(bus.drive(1), false); });
  EXPECT_EQ(r.fault.cause, control::FaultCause::device_lost);
  EXPECT_EQ(r.fault.index, 1u);
  EXPECT_EQ(r.fault.from, control::Phase::running);
  EXPECT_LE(r.fault.time_s, 3.0 + 0.3 + 0.02);
  EXPECT_NE(r.problem.find("ODrive node 2: no heartbeat"), std::string::npos) << r.problem;
}

TEST(CanFigure, AnOdriveAxisErrorFaultsItsChannelWithTheCauseNamed) {
  const CanRun r = play_can("odrive-arm.yaml", "odrive-arm.yaml", 200, [](assembly::SimulatedCanBus& bus) {
    dynamic_cast<sim::SimOdriveAxis&>(bus.drive(2)).inject_axis_error(0x40, 0);
  });
  EXPECT_EQ(r.fault.cause, control::FaultCause::device_error);
  EXPECT_EQ(r.fault.index, 2u);
  EXPECT_NE(r.problem.find("ODrive node 3: axis error 0x40"), std::string::npos) << r.problem;
}

TEST(CanFigure, ACia402DriveFaultEndsTheShowWithItsEmergencyCode) {
  // EMCY 0x7121: motor blocked, an overload.
  const CanRun r = play_can("cia402-turntable.yaml", "turntable-tour.yaml", 250, [](assembly::SimulatedCanBus& bus) {
    dynamic_cast<sim::SimCia402Drive&>(bus.drive(1)).raise_fault(0x7121);
  });
  EXPECT_EQ(r.fault.cause, control::FaultCause::device_overload);
  EXPECT_EQ(r.fault.index, 1u);
  EXPECT_NE(r.problem.find("CiA 402 node 6"), std::string::npos) << r.problem;
  EXPECT_NE(r.problem.find("7121"), std::string::npos) << r.problem;
}

TEST(CanFigure, AMissedCia402HeartbeatIsALostDrive) {
  const CanRun r = play_can("cia402-turntable.yaml", "turntable-tour.yaml", 250, [](assembly::SimulatedCanBus& bus) {
    dynamic_cast<sim::SimCia402Drive&>(bus.drive(0)).set_heartbeat_silent(true);
  });
  EXPECT_EQ(r.fault.cause, control::FaultCause::device_lost);
  EXPECT_EQ(r.fault.index, 0u);
  EXPECT_LE(r.fault.time_s, 2.5 + 0.3 + 0.02);
  EXPECT_NE(r.problem.find("no heartbeat"), std::string::npos) << r.problem;
}

TEST(CanFigure, ASilentMitMotorIsLost) {
  const CanRun r = play_can("cia402-turntable.yaml", "turntable-tour.yaml", 250,
                            [](assembly::SimulatedCanBus& bus) { bus.adapter().bus().set_attached(bus.drive(2), false); });
  EXPECT_EQ(r.fault.cause, control::FaultCause::device_lost);
  EXPECT_EQ(r.fault.index, 2u);
  EXPECT_NE(r.problem.find("MIT motor 16: no reply"), std::string::npos) << r.problem;
}

TEST(CanFigure, BusOffIsALinkFailure) {
  const CanRun r = play_can("odrive-arm.yaml", "odrive-arm.yaml", 150,
                            [](assembly::SimulatedCanBus& bus) { bus.adapter().bus().inject_bus_off(); });
  EXPECT_EQ(r.fault.cause, control::FaultCause::link_failure);
  EXPECT_EQ(r.fault.status, Status::io_error);
}

}  // namespace
}  // namespace avar
