#pragma once
// `avar play SHOW --rig RIG`: validate both files, open the links (real or simulated), ease in,
// play, ease out to rest, and report. With live inputs the controls mix over the show; `avar
// puppet` is the same run with no show (live only) and `avar record` keeps the take as keys.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "avar/control/realtime_setup.hpp"
#include "avar/session/timecode_run.hpp"

namespace avar::app {

struct PlayOptions {
  std::string show_path;
  std::optional<std::string> map_path;  ///< --map: show_path is a motion-capture file baked through this map
  std::string rig_path;
  std::optional<std::string> port;     ///< override the rig's single link's port
  bool simulate = false;               ///< --sim: simulate every link
  std::optional<double> rate_hz;       ///< default: the rig's rate_hz
  bool fast = false;                   ///< stepped simulated clock (simulator only)
  std::optional<std::uint64_t> loops;  ///< passes of a looping show; 0 = until Ctrl-C
  std::optional<std::string> trace_path;
  std::optional<std::string> plot_path;
  bool progress = true;  ///< progress line on the error stream while playing
  /// Loop-thread scheduling in real time: SCHED_FIFO 50 and locked memory unless told otherwise.
  control::RealtimeRequest realtime{50, true, -1};
  /// More deadline misses than this in one run is a fault.
  std::uint64_t deadline_miss_budget = UINT64_MAX;
  /// Wait for a start button (a digital input with role start) before moving anything.
  bool wait_start = false;

  // Live inputs (play, puppet, record).
  std::vector<std::string> inputs;         ///< --input URIs; none: play opens none, puppet/record the inputs section's devices
  std::optional<std::string> inputs_path;  ///< --inputs FILE; default: the rig file's inputs: section
  bool live_only = false;                  ///< no show: the figure holds its rest pose under the live layers
  std::optional<double> duration_s;        ///< live only: stop after this long (default: until Ctrl-C)
  std::optional<std::string> record_path;  ///< write the take (the mixed channels) as a show here
  double record_tolerance = 0.25;          ///< the take's keys stay this close to every tick's value (channel units)
  bool record_merge = false;               ///< write the take on its own layer over a copy of the show

  // Idle life (the rig's idle: section) below the show: --idle, `avar idle`.
  bool idle = false;
  std::optional<std::uint64_t> seed;     ///< default: a fresh one, printed in the summary
  double idle_before_s = 0;              ///< idle alone this long before the show plays
  double idle_after_s = 0;               ///< and after it ends
  session::ShowControlOptions timecode;  ///< --timecode (show time chases a timecode source), --osc-control
};

/// Runs the play command; returns the process exit code (see exit_codes.hpp). Messages go to
/// `out` (summary) and `err` (progress, warnings, errors).
int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
