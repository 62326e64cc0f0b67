#pragma once
// Command-line options of idle life: `avar play ... --idle [--seed N] [--idle-before S]
// [--idle-after S]` and the `avar idle` subcommand (idle only, like `avar puppet`).

#include <CLI/CLI.hpp>

#include "avar/play_command.hpp"

namespace avar::app {

/// --idle, --seed, --idle-before, --idle-after on `avar play`.
void add_idle_play_options(CLI::App* play, PlayOptions& options);

/// The `avar idle` subcommand with its own options (--seed, --fast); the caller adds the run
/// options every live run has (--rig, --sim, --duration, --trace ...).
CLI::App* add_idle_subcommand(CLI::App& app, PlayOptions& options);

}  // namespace avar::app
