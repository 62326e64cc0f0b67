#pragma once
// `avar inputs monitor|learn`: see what input devices send, and map controls to channels by
// moving them (MIDI learn, for every kind of input device).

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace avar::app {

struct InputsOptions {
  std::vector<std::string> inputs;   ///< device URIs (as play's --input)
  std::optional<double> duration_s;  ///< stop after this long (default: Ctrl-C; learn: when every channel is learned)
  // learn
  std::string rig_path;
  std::vector<std::string> channels;  ///< channels to learn, in order (default: every channel of the rig)
  std::string out_path;
  double timeout_s = 30;  ///< learn: give up on a channel after this long without a clear move
};

struct InputsCommands {
  CLI::App* monitor = nullptr;
  CLI::App* learn = nullptr;
};

/// Declares `inputs monitor` and `inputs learn` on `app`, writing into `options`.
InputsCommands add_inputs_subcommands(CLI::App& app, InputsOptions& options);

/// Prints every control as it moves ("ch1.cc7 = 0.504 (unipolar)"), at most 20 lines a second
/// per control, until Ctrl-C or the duration. Returns an exit code.
int run_inputs_monitor(const InputsOptions& options, std::ostream& out, std::ostream& err);

/// For each channel in turn: asks to move its control, takes the first control that sweeps at
/// least half of its range (ignoring ones already learned and jitter), and once every channel
/// has one writes an inputs file (devices and absolute mappings over each channel's limits) that
/// play, puppet and record read with --inputs. Returns an exit code.
int run_inputs_learn(const InputsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
