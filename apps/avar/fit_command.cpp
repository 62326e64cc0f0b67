#include "avar/fit_command.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "avar/config/show_writer.hpp"
#include "avar/config/show_file.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/option_error.hpp"
#include "avar/playback/offline/track_fit.hpp"
#include "avar/playback/offline/smoothing.hpp"
#include "avar/config/recording_csv.hpp"

namespace avar::app {

using config::read_recording;
using config::Recording;
using playback::fit_track;
using playback::max_fit_error;
namespace {

/// Sample rate of evenly spaced samples, or an InputError at the first row that breaks the spacing.
double even_sample_rate(const Recording& r, const std::string& path) {
  if (r.times.size() < 2) return 1;
  const double step = (r.times.back() - r.times.front()) / static_cast<double>(r.times.size() - 1);
  for (std::size_t i = 1; i < r.times.size(); ++i) {
    const double dt = r.times[i] - r.times[i - 1];
    if (std::abs(dt - step) > 0.01 * step)
      throw InputError({path, r.lines[i], 1}, "samples " + format_number(dt) + " s apart where the mean spacing is " +
                                                  format_number(step) +
                                                  " s; expected evenly spaced samples (within 1%) for --smooth");
  }
  return 1 / step;
}

}  // namespace

CLI::App* add_fit_subcommand(CLI::App& app, FitOptions& o) {
  CLI::App* cmd = app.add_subcommand("fit", "Turn recorded samples (CSV) into a show of few Bezier keys within a tolerance");
  cmd->add_option("csv", o.csv_path, "CSV file: a 'seconds' column, then one column per channel (as `avar sample` writes)")
      ->required();
  cmd->add_option("--tolerance", o.tolerance, "Largest allowed difference from the samples, in channel units (> 0)")
      ->required()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o.out_path, "Show file to write (YAML)")->required();
  cmd->add_option("--smooth", o.smooth, "Smooth first: none (default), moving_average, gaussian, bspline, butterworth")
      ->check(CLI::IsMember({"none", "moving_average", "gaussian", "bspline", "butterworth"}));
  cmd->add_option("--cutoff", o.cutoff_hz, "Smoothing cutoff frequency in Hz (needed with --smooth; below half the sample rate)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--corner-angle", o.corner_angle_deg,
                  "Turn (degrees) above which a sample is kept as a sharp corner (default 60)")
      ->check(CLI::Range(0.0, 180.0));
  cmd->footer(
      "Every channel becomes a track of Bezier keys with free handles: split at the worst sample until\n"
      "the show, sampled at every input time, stays within --tolerance of the input (of the smoothed\n"
      "input with --smooth), then every key the others can do without is dropped. End points and sharp\n"
      "corners (steps, kinks) are kept as keys.\n"
      "Per channel it prints samples in, keys out and the largest error of the written show.\n"
      "Examples:\n"
      "  avar sample examples/shows/hello-head.yaml --rate 100 --out head.csv\n"
      "  avar fit head.csv --tolerance 0.05 --out head-fitted.yaml\n"
      "      round trip a show through samples: the fitted show stays within 0.05 of every sample\n"
      "  avar fit recording.csv --tolerance 0.5 --smooth butterworth --cutoff 4 --out take1.yaml\n"
      "      a noisy 100 Hz recording, low-passed at 4 Hz without delay (zero phase), then fitted");
  return cmd;
}

int run_fit(const FitOptions& options, std::ostream& out, std::ostream& err) {
  try {
    const auto method = playback::smoothing_method_from_name(options.smooth);
    if (!method)
      throw option_error("--smooth",
                         "found '" + options.smooth + "'; expected none, moving_average, gaussian, bspline or butterworth");
    if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
      throw option_error("--tolerance", "expected above 0, found " + format_number(options.tolerance));
    if (*method != playback::SmoothingMethod::none && !options.cutoff_hz)
      throw option_error("--smooth", options.smooth + " needs --cutoff HZ; expected a cutoff frequency");
    const Recording recording = read_recording(options.csv_path);
    double rate = 0;
    if (*method != playback::SmoothingMethod::none) {
      rate = even_sample_rate(recording, options.csv_path);
      if (!(*options.cutoff_hz < 0.5 * rate))
        throw option_error("--cutoff", "expected below half the sample rate (" + format_number(0.5 * rate) + " Hz), found " +
                                           format_number(*options.cutoff_hz) + " Hz");
    }
    playback::Show show;
    show.name = std::filesystem::path(options.csv_path).stem().string();
    show.duration = recording.times.back();
    std::vector<std::vector<double>> targets;
    for (std::size_t c = 0; c < recording.channels.size(); ++c) {
      targets.push_back(*method == playback::SmoothingMethod::none
                            ? recording.values[c]
                            : playback::smooth(recording.values[c], *method, rate, *options.cutoff_hz));
      show.tracks.push_back(fit_track(recording.channels[c], recording.times, targets.back(), options.tolerance,
                                      options.corner_angle_deg, {options.csv_path, 1, 1}));
    }
    config::write_show_file(options.out_path, show, "written by avar fit");
    const playback::Show written = config::load_show_file(options.out_path);
    for (std::size_t c = 0; c < written.tracks.size(); ++c) {
      const auto& track = written.tracks[c];
      out << track.channel << ": " << recording.times.size() << " samples in, " << track.curve.key_count()
          << " keys out, max error " << format_number(max_fit_error(track.curve, recording.times, targets[c]));
      if (*method != playback::SmoothingMethod::none)
        out << " against the smoothed samples, "
            << format_number(max_fit_error(track.curve, recording.times, recording.values[c])) << " against the input";
      out << " (tolerance " << format_number(options.tolerance) << ")\n";
    }
    out << "wrote " << options.out_path << " (" << written.tracks.size() << " tracks, " << format_number(written.duration)
        << " s)\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
