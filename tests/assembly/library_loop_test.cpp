// The loop closed by the library alone, with no app code: a rig file and a show file are read,
// the figure's links are assembled from the protocol registry, and the controller reads its own
// feedback every tick.

#include <gtest/gtest.h>

#include <atomic>

#include "avar/assembly/figure_links.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "../support/stepped_figure_run.hpp"

namespace avar {
namespace {

class Unwatched final : public control::TickObserver {
 public:
  void after_tick(std::uint64_t, double, double, double, control::Controller&) override {}
};

TEST(LibraryLoop, DynamixelExampleOnTheSimulatorFaultsWhenAServoOverheats) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/dynamixel-arm.yaml");
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/arm-wave.yaml");
  ASSERT_TRUE(config::check_show_against_rig(show, rig).ok());
  const std::size_t shoulder = *rig.find_channel("shoulder");

  // The shoulder's servo (the second on the bus) comes up warm and holds a heavy prop: the
  // show's work takes it past its 80 °C limit, and only the simulated servo knows it.
  assembly::LinkSelection selection;
  selection.prepare_simulated = [](std::size_t, sim::ByteDevice& device) {
    auto& bus = dynamic_cast<sim::SimDynamixel&>(device);
    bus.set_temperature_c(1, 76);
    bus.set_external_load(1, 0.9);
  };
  assembly::FigureLinks figure(rig, selection);
  for (firmware_iface::ActuatorLink* link : figure.links()) ASSERT_EQ(link->start(), Status::ok);

  testing::SteppedFigureRun play(rig, show, figure);
  Unwatched nobody;
  const control::RunResult result = play.run(nobody);
  const control::Controller& controller = play.controller;
  EXPECT_LT(result.ticks, 2000u);  // the fault ended the run before the show's 8 s

  const control::Fault& fault = controller.latched_fault();
  EXPECT_EQ(fault.cause, control::FaultCause::device_overheat);
  EXPECT_EQ(fault.index, shoulder);
  EXPECT_GE(fault.value, 80);                      // the temperature the servo reported (whole °C) at its limit
  EXPECT_EQ(fault.from, control::Phase::running);  // mid-show, not at start
  EXPECT_FALSE(controller.active());
}

TEST(LibraryLoop, TheSimulatorsGroundTruthFeedsTheTrackingCheck) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  assembly::FigureLinks figure(rig, {});
  for (firmware_iface::ActuatorLink* link : figure.links()) ASSERT_EQ(link->start(), Status::ok);
  std::vector<double> measured(rig.channels.size(), 0.0);
  std::unique_ptr<bool[]> known(new bool[rig.channels.size()]());
  const std::span<bool> known_span(known.get(), rig.channels.size());
  figure.measure(measured, known_span);
  for (bool k : known_span) EXPECT_FALSE(k);  // nothing is known before the first step
  figure.advance(0.02);
  figure.measure(measured, known_span);
  for (std::size_t c = 0; c < rig.channels.size(); ++c) {
    EXPECT_TRUE(known[c]) << rig.channels[c].name;
    EXPECT_NEAR(measured[c], rig.channels[c].rest, 1e-6) << rig.channels[c].name;  // parked at rest
  }
}

}  // namespace
}  // namespace avar
