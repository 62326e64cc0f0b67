#include "avar/idle_options.hpp"

namespace avar::app {

void add_idle_play_options(CLI::App* play, PlayOptions& options) {
  CLI::Option* idle = play->add_flag("--idle", options.idle,
                                     "Idle life from the rig's idle: section below the show: it drives the channels the "
                                     "show leaves alone, and all of them before and after the show");
  play->add_option("--seed", options.seed, "Seed of idle life (default: a fresh one, printed; the same seed repeats a run)")
      ->needs(idle);
  play->add_option("--idle-before", options.idle_before_s, "Seconds of idle life before the show plays (default 0)")
      ->check(CLI::NonNegativeNumber)
      ->needs(idle);
  play->add_option("--idle-after", options.idle_after_s, "Seconds of idle life after the show ends (default 0)")
      ->check(CLI::NonNegativeNumber)
      ->needs(idle);
}

CLI::App* add_idle_subcommand(CLI::App& app, PlayOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "idle", "Idle life alone (the rig's idle: section: noise, blinks, gaze, breathing) until --duration or Ctrl-C");
  cmd->add_option("--seed", options.seed, "Seed (default: a fresh one, printed; the same seed repeats a run)");
  cmd->add_flag("--fast", options.fast, "Run on a simulated clock as fast as possible (simulator only; needs --duration)");
  cmd->footer(
      "Live inputs (--input) still mix over idle life, as in `avar puppet`. Examples:\n"
      "  avar idle --rig examples/rigs/hello-head.yaml --sim\n"
      "  avar idle --rig examples/rigs/hello-head.yaml --sim --fast --duration 60 --seed 7 --trace idle.csv");
  return cmd;
}

}  // namespace avar::app
