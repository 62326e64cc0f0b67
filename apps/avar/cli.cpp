#include "avar/cli.hpp"

#include <CLI/CLI.hpp>

#include <ostream>

#include "avar/check_command.hpp"
#include "avar/exit_codes.hpp"
#include "avar/export_command.hpp"
#include "avar/fit_command.hpp"
#include "avar/idle_options.hpp"
#include "avar/inputs_command.hpp"
#include "avar/mocap_bake_command.hpp"
#include "avar/mocap_command.hpp"
#include "avar/jaw_command.hpp"
#include "avar/play_command.hpp"
#include "avar/studio_command.hpp"
#include "avar/sample_command.hpp"
#include "avar/sim_command.hpp"
#include "avar/timecode_options.hpp"
#include "avar/visemes_command.hpp"

namespace avar::app {

namespace {

/// The options play, puppet and record share, and their parsed values.
struct RunCli {
  PlayOptions options;
  double rate = 0;
  std::uint64_t loops = 0;
  double duration = 0;
  std::string port, trace, plot, record_out;
  bool no_progress = false, no_lock = false;
  CLI::Option *port_opt = nullptr, *rate_opt = nullptr, *loops_opt = nullptr, *trace_opt = nullptr, *plot_opt = nullptr,
              *duration_opt = nullptr;

  PlayOptions& finish() {
    if (port_opt && *port_opt) options.port = port;
    if (*rate_opt) options.rate_hz = rate;
    if (loops_opt && *loops_opt) options.loops = loops;
    if (*trace_opt) options.trace_path = trace;
    if (*plot_opt) options.plot_path = plot;
    if (duration_opt && *duration_opt) options.duration_s = duration;
    options.progress = !no_progress;
    options.realtime.lock_memory = !no_lock;
    return options;
  }
};

void declare_run_options(CLI::App* cmd, RunCli& r, bool plays_show) {
  PlayOptions& o = r.options;
  cmd->add_option("--rig", o.rig_path, "Rig file (YAML: links, channels, actuators, optional inputs:)")->required();
  r.port_opt = cmd->add_option("--port", r.port, "Serial port for the rig's link, e.g. /dev/ttyACM0 (overrides the rig)");
  CLI::Option* sim_opt = cmd->add_flag("--sim", o.simulate, "Simulate every link, whatever ports the rig names");
  r.port_opt->excludes(sim_opt);
  r.rate_opt = cmd->add_option("--rate", r.rate, "Ticks per second, 1 to 1000 (default: the rig's rate_hz)")
                   ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--input", o.inputs,
                  "Live input device, repeatable: osc://HOST:PORT (UDP, default host 127.0.0.1), midi:NAME (a MIDI port "
                  "whose name contains NAME, or its number), hid:VID:PID[:SERIAL] (hex ids); NAME=URI prefixes its controls "
                  "with NAME.");
  cmd->add_option("--inputs", o.inputs_path, "Inputs file (YAML with an inputs: section; default: the rig's own inputs:)");
  if (plays_show) {
    // The wall clock is the default and has no flag; --fast asks for the simulated one.
    cmd->add_flag("--fast", o.fast,
                  "Run on a simulated clock as fast as possible (simulator only, deterministic; default: the wall clock)");
    r.loops_opt = cmd->add_option("--loops", r.loops, "Passes of a looping show (0 = until Ctrl-C; default 0, or 1 with --fast)");
    declare_show_control_options(cmd, o.timecode);
  } else {
    r.duration_opt =
        cmd->add_option("--duration", r.duration, "Without a show: stop after this many seconds (default: at Ctrl-C)")
            ->check(CLI::PositiveNumber);
  }
  r.trace_opt = cmd->add_option("--trace", r.trace, "Write every tick to this CSV file (live controls as input.NAME columns)");
  r.plot_opt = cmd->add_option("--plot", r.plot, "Write an SVG plot of commanded vs simulated position per channel");
  cmd->add_flag("--no-progress", r.no_progress, "Do not draw the progress line");
  cmd->add_option("--priority", o.realtime.priority,
                  "SCHED_FIFO priority of the loop, 1 to 99 (default 50); 0 = normal scheduling")
      ->check(CLI::Range(0, 99));
  cmd->add_option("--cpu", o.realtime.cpu, "Pin the loop thread to this CPU (default: any)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--deadline-budget", o.deadline_miss_budget,
                  "Deadline misses allowed in one run before it faults (default: unlimited)");
  cmd->add_flag("--no-lock-memory", r.no_lock, "Do not lock the process's memory against paging");
  cmd->add_flag("--wait-start", o.wait_start,
                "Wait for a press of the rig's start button (digital_inputs: with role: start) before moving anything");
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{"avar: play keyframed shows on animatronic figures, real or simulated"};
  app.footer(
      "Examples:\n"
      "  avar play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml\n"
      "      play on the rig's links (here a simulated Maestro), in real time\n"
      "  avar play SHOW --rig RIG --fast --plot out.svg\n"
      "      play on the simulator on a simulated clock and plot commanded vs simulated positions\n"
      "  avar play SHOW --rig RIG --port /dev/ttyACM0\n"
      "      drive a real Maestro (its USB command port) instead of the rig's port\n"
      "  avar check SHOW --rig RIG [--retime OUT.yaml]\n"
      "      validate both files and list what the rig cannot do, without moving anything\n"
      "  avar sample SHOW --rate 100 --channels neck_pan,jaw\n"
      "      write the show's curves as CSV, to inspect, plot or diff (no rig needed)\n"
      "  avar fit recording.csv --tolerance 0.1 --out take.yaml [--smooth butterworth --cutoff 4]\n"
      "      turn recorded samples into a show of few Bezier keys within the tolerance\n"
      "  avar export SHOW --rig RIG --target atmega328p --out DIR\n"
      "      a library that plays the show on a microcontroller (an Uno with a PCA9685 board), standalone\n"
      "  avar mocap info walk.bvh   /   avar mocap joints walk.bvh --out joints.csv\n"
      "      show a motion-capture file's skeleton, or write its joints' positions per frame as CSV\n"
      "  avar jaw voice.wav --rig RIG --channel jaw --out jaw.yaml\n"
      "      a talking figure's jaw track from a voice recording\n"
      "  avar visemes voice.tsv --rig RIG --out lips.yaml\n"
      "      lip-sync tracks from Rhubarb or Papagayo mouth cues through the rig's visemes: table\n"
      "  avar sim maestro   /   avar sim dynamixel --ids 1,2,3   /   avar sim feetech|ssc32|dmx|artnet|sacn\n"
      "      run a simulated device and print where other programs reach it (a serial port, or HOST:PORT)\n"
      "  avar sim avar-device --channels 8\n"
      "      a board running avar's streaming player: a rig link avar-device: {} streams curve knots to it\n"
      "  avar sim odrive --ids 1,2,3   /   avar sim can --drive cia402 --ids 5   (can is also slcan)\n"
      "      a simulated SLCAN adapter (CANable-like) with simulated CAN drives behind it\n"
      "Exit codes: 0 done, 2 bad input (nothing moved), 3 fault during the show, 130 interrupted.");
  app.require_subcommand(1);

  RunCli play, puppet, record;
  CLI::App* play_cmd = app.add_subcommand("play", "Play a show on a rig: ease in from the present pose, play, ease out to rest");
  play_cmd->add_option("show", play.options.show_path, "Show file (YAML: duration, loop, tracks of keys), or a .bvh with --map")
      ->required();
  play_cmd->add_option("--map", play.options.map_path, "Retarget map: play a motion-capture file (baked in memory) through it");
  declare_run_options(play_cmd, play, true);
  add_idle_play_options(play_cmd, play.options);
  play_cmd->footer(
      "Live inputs (--input, repeatable) mix over the show through the rig's inputs: mappings; the\n"
      "limiter and supervisor still hold every channel to its limits. Examples:\n"
      "  avar play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml --fast --plot head.svg\n"
      "  avar play SHOW --rig RIG --input osc://127.0.0.1:9000 --input pad=hid:054c:09cc --trace run.csv");

  CLI::App* puppet_cmd =
      app.add_subcommand("puppet", "Drive a figure live from input devices, with no show (Ctrl-C eases to rest)");
  declare_run_options(puppet_cmd, puppet, false);
  puppet_cmd->footer(
      "Every channel holds its rest pose until a control mapped to it (the inputs: section of the rig\n"
      "or of --inputs FILE) moves it. Without --input the devices listed in that section open.\n"
      "OSC: /avar/control/NAME f V sets a control, /avar/channel/NAME f V a channel in its units.\n"
      "Examples:\n"
      "  avar puppet --rig examples/rigs/hello-head.yaml --sim --input osc://127.0.0.1:9000\n"
      "      then: oscsend localhost 9000 /avar/channel/jaw f 20\n"
      "  avar puppet --rig RIG --inputs my-pad.yaml --input pad=hid:054c:09cc");

  CLI::App* record_cmd = app.add_subcommand(
      "record", "Record a live performance (the channels after mixing, every tick) as a show of editable keys");
  record_cmd->add_option("--show", record.options.show_path, "Perform over this show (default: no show, live only)");
  record_cmd->add_option("--out", record.record_out, "Show file to write the take to (YAML)")->required();
  record_cmd
      ->add_option("--tolerance", record.options.record_tolerance,
                   "Largest difference of the keys from every recorded tick, channel units (default 0.25)")
      ->check(CLI::PositiveNumber);
  record_cmd->add_flag("--merge", record.options.record_merge,
                       "Write a copy of --show with the take as a clip on a layer of its own ('take') over it");
  declare_run_options(record_cmd, record, false);
  record_cmd->footer(
      "The take holds the channels a live control moved, as commanded (after mixing and limits), fitted\n"
      "with few Bezier keys within --tolerance. Ctrl-C (or --duration, or the show's end) ends the take\n"
      "and keeps it. Examples:\n"
      "  avar record --rig RIG --sim --input osc://127.0.0.1:9000 --duration 20 --out take.yaml\n"
      "  avar record --rig RIG --show SHOW --merge --input midi:nano --out show-with-take.yaml");

  RunCli idle;
  CLI::App* idle_cmd = add_idle_subcommand(app, idle.options);
  declare_run_options(idle_cmd, idle, false);

  std::string check_show, check_rig;
  CLI::App* check_cmd = app.add_subcommand("check", "Validate a show against a rig and report every problem, moving nothing");
  check_cmd->add_option("show", check_show, "Show file")->required();
  check_cmd->add_option("--rig", check_rig, "Rig file")->required();
  std::string retime;
  check_cmd->add_option("--retime", retime,
                        "Write a version of the show whose too-fast segments are stretched just enough (OUT.yaml)");
  check_cmd->footer(
      "Reads the rig and the show whole, and the rig's inputs: section, and opens no port. It prints:\n"
      "  error: FILE:LINE:COL: what was found, what was expected   (stderr; exit 2, the show cannot play)\n"
      "  warning: ...   what playback will change, such as a Bezier handle overshooting a limit (clamped)\n"
      "  ok: show 'NAME' (4 s, 2 tracks, 7 keys) fits rig 'NAME' (8 channels, 8 actuators, 1 link(s))\n"
      "  infeasible: show.yaml:5:7: neck_tilt 0-0.05 s: speed 580 deg/s, allowed 220 deg/s\n"
      "      a segment (from the key at that line) that asks more speed, acceleration or range than the\n"
      "      channel allows: what it needs against what is allowed\n"
      "  step: show.yaml:10:7: jaw 0.5-1.5 s: jumps by 25 deg at once (step)   a step key's jump\n"
      "  then a count of both. The limiter slows or clamps them at playback, so the figure stays safe\n"
      "either way; --retime writes a show that asks no more than the rig allows. Exit 0 when the show can\n"
      "play. Examples:\n"
      "  avar check examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml\n"
      "  avar check my-show.yaml --rig my-rig.yaml --retime my-show-retimed.yaml");

  SampleOptions sample;
  CLI::App* sample_cmd = add_sample_subcommand(app, sample);
  FitOptions fit;
  CLI::App* fit_cmd = add_fit_subcommand(app, fit);
  ExportOptions export_options;
  CLI::App* export_cmd = add_export_subcommand(app, export_options);
  JawCommandOptions jaw;
  CLI::App* jaw_cmd = add_jaw_subcommand(app, jaw);
  VisemesCommandOptions visemes;
  CLI::App* visemes_cmd = add_visemes_subcommand(app, visemes);

  MocapOptions mocap;
  const MocapCommands mocap_cmds = add_mocap_subcommands(app, mocap);

  InputsOptions inputs;
  const InputsCommands inputs_cmds = add_inputs_subcommands(app, inputs);

  MocapBakeOptions mocap_bake;
  CLI::App* mocap_bake_cmd = add_mocap_bake_subcommand(*mocap_cmds.mocap, mocap_bake);

  SimCommands sims;
  add_sim_subcommands(app, sims);

  StudioOptions studio;
  CLI::App* studio_cmd = add_studio_subcommand(app, studio);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    app.exit(e, out, err);
    return kExitBadInput;
  }

  if (*play_cmd) return run_play(play.finish(), out, err);
  if (*puppet_cmd) {
    puppet.options.live_only = true;
    return run_play(puppet.finish(), out, err);
  }
  if (*record_cmd) {
    record.options.live_only = record.options.show_path.empty();
    record.options.record_path = record.record_out;
    return run_play(record.finish(), out, err);
  }
  if (*idle_cmd) {
    idle.options.live_only = true;
    idle.options.idle = true;
    return run_play(idle.finish(), out, err);
  }
  if (*inputs_cmds.monitor) return run_inputs_monitor(inputs, out, err);
  if (*inputs_cmds.learn) return run_inputs_learn(inputs, out, err);
  if (*mocap_bake_cmd) return run_mocap_bake(mocap_bake, out, err);
  if (*mocap_cmds.mocap) return run_mocap(mocap_cmds, mocap, out, err);
  if (*check_cmd) return run_check(check_show, check_rig, retime, out, err);
  if (*sample_cmd) return run_sample(sample, out, err);
  if (*fit_cmd) return run_fit(fit, out, err);
  if (*export_cmd) return run_export(export_options, out, err);
  if (*jaw_cmd) return run_jaw(jaw, out, err);
  if (*visemes_cmd) return run_visemes(visemes, out, err);
  if (*sims.sim) return run_sim(sims, out, err);
  if (*studio_cmd) return run_studio(studio, out, err);
  return kExitBadInput;
}

}  // namespace avar::app
