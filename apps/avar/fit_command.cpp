#include "avar/fit_command.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <stdexcept>
#include <vector>

#include "avar/config/show_writer.hpp"
#include "avar/config/show_file.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/playback/offline/curve_fit.hpp"
#include "avar/playback/offline/smoothing.hpp"

namespace avar::app {
namespace {

/// A bad command-line value, reported like a file problem with the option as its place.
InputError option_error(const std::string& option, const std::string& problem) { return InputError({option, 0, 0}, problem); }

/// The samples of a CSV: one time column, one value column per channel.
struct Recording {
  std::vector<std::string> channels;
  std::vector<double> times;
  std::vector<std::vector<double>> values;  ///< [channel][row]
  std::vector<int> lines;                   ///< file line of each row
};

struct Cell {
  std::string text;
  int column = 1;  ///< 1-based character column where the cell starts
};

std::vector<Cell> split_cells(const std::string& line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string::npos ? line.size() : comma;
    std::string text = line.substr(start, end - start);
    const auto first = text.find_first_not_of(" \t");
    const auto last = text.find_last_not_of(" \t");
    text = first == std::string::npos ? "" : text.substr(first, last - first + 1);
    cells.push_back({text, static_cast<int>(start) + 1});
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

double parse_number(const std::string& path, int line, const Cell& cell, const std::string& column_name) {
  double value = 0;
  const char* begin = cell.text.data();
  const char* end = begin + cell.text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  const SourceLocation where{path, line, cell.column};
  if (cell.text.empty() || ec != std::errc() || ptr != end)
    throw InputError(where, "found '" + cell.text + "' in column '" + column_name + "'; expected a number");
  if (!std::isfinite(value))
    throw InputError(where, "found " + cell.text + " in column '" + column_name + "'; expected a finite number");
  return value;
}

Recording read_recording(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError({path, 0, 0}, "cannot open the file; expected a readable CSV file (as `avar sample` writes)");
  Recording r;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(file, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::vector<Cell> cells = split_cells(line);
    if (!header) {
      header = true;
      if (cells[0].text != "seconds")
        throw InputError({path, number, cells[0].column},
                         "found '" + cells[0].text + "' as the first column; expected the header to start with 'seconds'");
      if (cells.size() < 2) throw InputError({path, number, 1}, "found only 'seconds' in the header; expected at least one channel column");
      std::set<std::string> seen;
      for (std::size_t c = 1; c < cells.size(); ++c) {
        if (cells[c].text.empty()) throw InputError({path, number, cells[c].column}, "found an empty channel name; expected a name");
        if (!seen.insert(cells[c].text).second)
          throw InputError({path, number, cells[c].column}, "channel '" + cells[c].text + "' appears twice; expected each channel once");
        r.channels.push_back(cells[c].text);
      }
      r.values.resize(r.channels.size());
      continue;
    }
    if (cells.size() != r.channels.size() + 1)
      throw InputError({path, number, 1}, "found " + std::to_string(cells.size()) + " cells; expected " +
                                              std::to_string(r.channels.size() + 1) + " (seconds and the " +
                                              std::to_string(r.channels.size()) + " channels of the header)");
    const double t = parse_number(path, number, cells[0], "seconds");
    if (t < 0)
      throw InputError({path, number, cells[0].column},
                       "found time " + format_number(t) + " s; expected times of 0 s or more (show keys lie within the show)");
    if (!r.times.empty() && !(t > r.times.back()))
      throw InputError({path, number, cells[0].column}, "time " + format_number(t) + " s is not after the previous row's " +
                                                            format_number(r.times.back()) + " s; expected times to strictly increase");
    r.times.push_back(t);
    r.lines.push_back(number);
    for (std::size_t c = 0; c < r.channels.size(); ++c) r.values[c].push_back(parse_number(path, number, cells[c + 1], r.channels[c]));
  }
  if (!header) throw InputError({path, 1, 1}, "the file is empty; expected a header 'seconds,<channel>,...' and rows of samples");
  if (r.times.empty()) throw InputError({path, number, 1}, "found no rows after the header; expected at least one row of samples");
  if (!(r.times.back() > 0))
    throw InputError({path, r.lines.back(), 1}, "the samples end at 0 s; expected the last sample after 0 s (the show's duration)");
  return r;
}

/// Sample rate of evenly spaced samples, or an InputError at the first row that breaks the spacing.
double even_sample_rate(const Recording& r, const std::string& path) {
  if (r.times.size() < 2) return 1;
  const double step = (r.times.back() - r.times.front()) / static_cast<double>(r.times.size() - 1);
  for (std::size_t i = 1; i < r.times.size(); ++i) {
    const double dt = r.times[i] - r.times[i - 1];
    if (std::abs(dt - step) > 0.01 * step)
      throw InputError({path, r.lines[i], 1}, "samples " + format_number(dt) + " s apart where the mean spacing is " +
                                                  format_number(step) + " s; expected evenly spaced samples (within 1%) for --smooth");
  }
  return 1 / step;
}

double max_error(const playback::Curve& curve, const std::vector<double>& t, const std::vector<double>& v) {
  double worst = 0;
  playback::CurveCursor cursor;
  for (std::size_t i = 0; i < t.size(); ++i) worst = std::max(worst, std::abs(curve.evaluate(t[i], cursor) - v[i]));
  return worst;
}

}  // namespace

CLI::App* add_fit_subcommand(CLI::App& app, FitOptions& o) {
  CLI::App* cmd = app.add_subcommand("fit", "Turn recorded samples (CSV) into a show of few Bezier keys within a tolerance");
  cmd->add_option("csv", o.csv_path, "CSV file: a 'seconds' column, then one column per channel (as `avar sample` writes)")->required();
  cmd->add_option("--tolerance", o.tolerance, "Largest allowed difference from the samples, in channel units (> 0)")
      ->required()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o.out_path, "Show file to write (YAML)")->required();
  cmd->add_option("--smooth", o.smooth, "Smooth first: none (default), moving_average, gaussian, bspline, butterworth")
      ->check(CLI::IsMember({"none", "moving_average", "gaussian", "bspline", "butterworth"}));
  cmd->add_option("--cutoff", o.cutoff_hz, "Smoothing cutoff frequency in Hz (needed with --smooth; below half the sample rate)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--corner-angle", o.corner_angle_deg, "Turn (degrees) above which a sample is kept as a sharp corner (default 60)")
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
    if (!method) throw option_error("--smooth", "found '" + options.smooth + "'; expected none, moving_average, gaussian, bspline or butterworth");
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
      playback::CurveFitOptions fit_options;
      // A hair inside the tolerance, so that the written decimal numbers cannot push a sample over.
      fit_options.tolerance = options.tolerance * (1 - 1e-9);
      fit_options.corner_angle_deg = options.corner_angle_deg;
      const SourceLocation where{options.csv_path, 1, 1};
      playback::Track track;
      track.channel = recording.channels[c];
      track.where = where;
      track.raw = playback::fit_curve(recording.times, targets.back(), fit_options, where).curve;
      track.curve = playback::Curve::build(track.raw);
      show.tracks.push_back(std::move(track));
    }
    config::write_show_file(options.out_path, show, "written by avar fit");
    const playback::Show written = config::load_show_file(options.out_path);
    for (std::size_t c = 0; c < written.tracks.size(); ++c) {
      const auto& track = written.tracks[c];
      out << track.channel << ": " << recording.times.size() << " samples in, " << track.curve.key_count()
          << " keys out, max error " << format_number(max_error(track.curve, recording.times, targets[c]));
      if (*method != playback::SmoothingMethod::none)
        out << " against the smoothed samples, " << format_number(max_error(track.curve, recording.times, recording.values[c]))
            << " against the input";
      out << " (tolerance " << format_number(options.tolerance) << ")\n";
    }
    out << "wrote " << options.out_path << " (" << written.tracks.size() << " tracks, " << format_number(written.duration) << " s)\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
