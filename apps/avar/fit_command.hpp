#pragma once
// `avar fit IN.csv --tolerance X --out SHOW.yaml`: turns recorded samples (the CSV `avar sample`
// writes: `seconds`, then one column per channel) into a show of few Bezier keys per channel
// whose sampled values stay within the tolerance of the samples at every sample time.

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace avar::app {

struct FitOptions {
  std::string csv_path;
  std::string out_path;
  double tolerance = 0;                  ///< channel units, > 0
  std::string smooth = "none";           ///< none | moving_average | gaussian | bspline | butterworth
  std::optional<double> cutoff_hz;       ///< needed by every smoothing method
  double corner_angle_deg = 60;          ///< see playback::CurveFitOptions
};

/// Declares the `fit` subcommand and its options on `app`, writing into `options`.
CLI::App* add_fit_subcommand(CLI::App& app, FitOptions& options);

/// Reads and validates the whole CSV (InputError with file, line, column: empty file, a header
/// that does not start with `seconds` or has no channel, empty or repeated channel names, rows
/// with another cell count than the header, cells that are not finite numbers, times below 0 or
/// not strictly increasing, no rows, samples spanning no time; with --smooth, unevenly spaced
/// samples), smooths each channel if asked, fits it (playback::fit_curve), writes the show
/// (duration = the last sample time, keys Bezier with free handles), loads it back with the show
/// loader and prints, per channel, samples in, keys out and the largest error of the loaded
/// show against the samples it fitted (and against the raw input when smoothing). Returns
/// kExitOk, or kExitBadInput after one line on `err` naming the problem.
int run_fit(const FitOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
