#pragma once
// `avar visemes CUES --rig RIG --out SHOW.yaml`: lip sync from a lip-sync tool's mouth cues
// (Rhubarb TSV or JSON, Papagayo/Moho .dat) through the rig's `visemes:` table, blended with
// coarticulation, one fitted track per posed channel, checked against the rig.

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace avar::app {

struct VisemesCommandOptions {
  std::string cues_path;
  std::string rig_path;
  std::string out_path;
  double fps = 24;  ///< frames per second of a Moho switch file
  std::optional<double> rise_ms, decay_ms;
  std::optional<double> tolerance;   ///< default: 1% of each channel's pose span
  std::optional<double> duration_s;  ///< default: the last cue + 0.5 s
};

CLI::App* add_visemes_subcommand(CLI::App& app, VisemesCommandOptions& options);

/// Loads the rig and its visemes table, reads the cues, blends and fits them, writes the show,
/// then checks it against the rig as `avar check` does. Returns kExitOk, or kExitBadInput after
/// one line on `err` naming the file or option and what was expected.
int run_visemes(const VisemesCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
