#pragma once
// One run of a figure, as every front end starts it: the show session with what plays around
// it, opened and wired in one place. `avar play`, `puppet`, `record` and `idle` are this with
// different setups; a studio or a show-network node is the same run with other commands.
//
//   FigureRun run(rig, show, input_map, setup);  // opens everything; nothing moves yet
//   run.watch_inputs();                          // the GPIO e-stop is watched from here
//   run.wait_for_start_button(interrupts);        // optional: a start button of the rig
//   if (auto problem = run.start()) ...           // the links; homing from the devices' pose
//   run.session().add_observer(recorder);         // any SessionObserver, before run()
//   control::RunResult r = run.run(interrupts, &keyboard_estop);
//
// What it owns, in the order the constructor opens them (a failure leaves nothing running and
// nothing moved): the live inputs (the setup's input devices, and the rig's digital inputs with
// the control role, mixed over the show by the inputs map), the show-time source (a chased
// timecode, started; or the OSC control surface, bound), the show session and its links, the
// rig's digital inputs (opened; watched from watch_inputs()). Idle life, when asked for, is a
// layer under the live inputs. The show's OSC cues fire from the loop by show time. Every e-stop
// (the caller's, the digital inputs', the control surface's) goes to the session.
//
// Threads: construct, start and run on one thread; the session's commands from any thread.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "avar/config/input_map.hpp"
#include "avar/control/runner.hpp"
#include "avar/inputs/gpio_inputs.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"
#include "avar/session/cue_player.hpp"
#include "avar/session/idle_session.hpp"
#include "avar/session/live_session.hpp"
#include "avar/session/osc_control.hpp"
#include "avar/session/show_session.hpp"
#include "avar/session/timecode_run.hpp"

namespace avar::session {

struct FigureRunSetup {
  /// Rate, clock, links, loops, lead-in and lead-out, scheduling, deadline budget. Its live,
  /// recorded_controls and external_clock are the run's to set from what it opens.
  SessionConfig session;
  /// Live input devices (osc://HOST:PORT, midi:NAME, hid:VID:PID); none: no device, though the
  /// rig's control digital inputs still feed the inputs map.
  std::vector<std::string> input_uris;
  /// Set: the rig's idle life (its idle: section) under the show, from this seed.
  std::optional<std::uint64_t> idle_seed;
  /// Show time from a timecode source or an OSC control surface (at most one of them).
  ShowControlOptions show_control;
};

/// What `avar puppet` and `avar idle` play: no tracks (every channel holds its rest pose under
/// the live layers), for `duration_s` seconds, or without end.
playback::Show live_only_show(std::optional<double> duration_s);

/// True when the rig has a digital input with the control role (a button as a live control).
bool has_control_inputs(const rig::Rig& rig);

/// How wait_for_start_button() ended.
enum class StartWait {
  pressed,      ///< a start button was pressed
  interrupted,  ///< Ctrl-C before it was: nothing moved
  estop,        ///< the e-stop is pressed: release and reset it first
  no_button,    ///< the rig has no digital input with role start
};

class FigureRun {
 public:
  /// Validates the setup whole, then opens (see the file comment). `rig`, `show` and `map` are
  /// borrowed and outlive the run. Throws InputError (a file's mistake, file:line:col),
  /// NeedsSimulatedLinks (a stepped run with a real link), std::invalid_argument (a malformed
  /// spec or address, both timecode and a control surface) or std::runtime_error (a device, port
  /// or socket that cannot be opened), each naming what was expected.
  FigureRun(const rig::Rig& rig, const playback::Show& show, const config::InputMap& map, FigureRunSetup setup);
  ~FigureRun();
  FigureRun(const FigureRun&) = delete;
  FigureRun& operator=(const FigureRun&) = delete;

  /// Starts watching the rig's digital inputs (an e-stop held now is seen before anything
  /// moves; control inputs post into the live inputs). std::runtime_error when a line cannot
  /// be read. Nothing to do for a rig without digital inputs.
  void watch_inputs();
  /// Blocks until a start button of the rig is pressed (after watch_inputs()), Ctrl-C counted
  /// in `interrupts`, or the e-stop. Polls every 10 ms; nothing is commanded meanwhile.
  StartWait wait_for_start_button(const std::atomic<int>& interrupts) const;
  /// The rig's start buttons, quoted and separated by commas ("'go', 'red'"); empty: none.
  std::string start_button_names() const;

  /// Starts every link, then begins the session (homing from the pose the devices report).
  /// The first link that did not start is returned, and nothing has moved.
  std::optional<LinkProblem> start();
  /// Runs to the end (see ShowSession::run). `keyboard_estop` (borrowed; nullptr: none) is an
  /// e-stop beside the digital inputs' and the control surface's. Afterwards every fired cue
  /// was sent and every source is stopped.
  control::RunResult run(const std::atomic<int>& interrupts, const std::atomic<bool>* keyboard_estop);

  ShowSession& session() noexcept { return *session_; }
  const ShowSession& session() const noexcept { return *session_; }
  /// The parts, for front ends that report them; nullptr where the setup asked for none.
  const LiveSession* live() const noexcept { return live_.get(); }
  LiveSession* live() noexcept { return live_.get(); }
  const IdleSession* idle() const noexcept { return idle_.get(); }
  const TimecodeRun* chase() const noexcept { return chase_.get(); }
  const OscControlSurface* surface() const noexcept { return surface_.get(); }
  const CuePlayer& cues() const noexcept { return cues_; }
  /// Live controls every tick record carries (RecorderOptions::controls).
  std::size_t recorded_controls() const noexcept;

 private:
  const rig::Rig& rig_;
  std::unique_ptr<LiveSession> live_;
  std::unique_ptr<TimecodeRun> chase_;
  std::unique_ptr<OscControlSurface> surface_;
  std::unique_ptr<IdleSession> idle_;
  std::shared_ptr<assembly::GpioChips> gpio_chips_;
  std::unique_ptr<ShowSession> session_;
  std::unique_ptr<inputs::GpioInputs> digital_inputs_;
  CuePlayer cues_;
};

}  // namespace avar::session
