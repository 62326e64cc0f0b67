#pragma once
// `avar jaw AUDIO --rig RIG --channel jaw --out SHOW.yaml`: a talking figure's jaw from a voice
// recording (WAV, FLAC, OGG), as a show of one fitted track, checked against the rig.

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace avar::app {

struct JawCommandOptions {
  std::string audio_path;
  std::string rig_path;
  std::string channel = "jaw";
  std::string out_path;
  std::optional<double> gate_db;  ///< envelope level that opens the gate (dBFS)
  std::optional<double> full_db;  ///< level at which the jaw is fully open (dBFS)
  std::optional<double> hysteresis_db;
  std::optional<double> attack_ms, release_ms;
  std::optional<std::string> band;  ///< "LO-HI" in Hz
  std::optional<double> lead_ms;    ///< default: from the channel's speed and acceleration limits
  std::optional<double> curve;
  std::optional<double> closed, open;  ///< default: the channel's rest, and the limit farther from it
  std::optional<double> tolerance;     ///< default: 1% of the travel
  bool verbose = false;                ///< list every segment's share of the limits, not a summary
};

/// Declares the `jaw` subcommand and its options on `app`, writing into `options`.
CLI::App* add_jaw_subcommand(CLI::App& app, JawCommandOptions& options);

/// Loads the rig, derives the jaw's range and lead from its channel unless given, runs the jaw
/// pipeline on the audio, fits it, writes the show (duration = the audio's), then checks the
/// written show against the rig as `avar check` does (warnings and infeasible segments listed).
/// Prints progress on `out`. Returns kExitOk, or kExitBadInput after one line on `err` naming
/// the file or option and what was expected.
int run_jaw(const JawCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
