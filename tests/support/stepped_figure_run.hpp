#pragma once
// A show played by the library alone on an assembled figure, as `avar play --fast` plays it: the
// stepped clock, the figure as the plant, its simulated ground truth as the position feedback.

#include <atomic>

#include "avar/assembly/figure_links.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"

namespace avar::testing {

struct SteppedFigureRun {
  SteppedFigureRun(const rig::Rig& rig, const playback::Show& show, assembly::FigureLinks& figure)
      : rig_(rig), figure_(figure), controller(rig, show, figure.links(), options(rig, figure)) {
    controller.begin(0.0, rig.rest_frame());
  }

  /// Runs to the end of the show or the first fault; `observer` sees every tick.
  control::RunResult run(control::TickObserver& observer) {
    control::RunOptions run{rig_.rate_hz, control::ClockMode::stepped, {}};
    run.plant = &figure_;
    const std::atomic<int> no_interrupts{0};
    return control::run_loop(controller, run, observer, no_interrupts);
  }

 private:
  static control::ControllerOptions options(const rig::Rig& rig, assembly::FigureLinks& figure) {
    control::ControllerOptions o;
    o.tick_period_s = 1.0 / rig.rate_hz;
    o.stage_clock = nullptr;
    o.positions = &figure;
    return o;
  }

  const rig::Rig& rig_;
  assembly::FigureLinks& figure_;

 public:
  control::Controller controller;
};

}  // namespace avar::testing
