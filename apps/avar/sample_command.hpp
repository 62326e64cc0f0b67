#pragma once
// `avar sample SHOW`: the show's curves evaluated on a regular time grid, as CSV, so users can
// inspect, plot and diff them. Needs no rig and moves nothing.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace avar::app {

struct SampleOptions {
  std::string show_path;
  std::optional<double> rate_hz;          ///< samples per second; default kDefaultSampleRateHz
  std::optional<double> step_s;           ///< seconds between samples (instead of rate_hz)
  std::optional<double> from_s;           ///< first sample time (s); default 0
  std::optional<double> to_s;             ///< last sample time (s); default the show's duration
  std::vector<std::string> channels;      ///< columns in this order; empty: every track, in file order
  std::optional<std::string> out_path;    ///< write the CSV here instead of `out`
  std::optional<std::string> rig_path;    ///< a layered show is composed over this rig's rest pose
  /// "double" (avar's reference engine) or "device" (the device engine's host build: the show
  /// encoded as a device image over the rig's channel ranges, 16-bit output back in channel units)
  std::string engine = "double";
};

inline constexpr double kDefaultSampleRateHz = 100;
/// Sample spacing below this (seconds) is refused: sample times are rounded to the nanosecond.
inline constexpr double kMinSampleStepS = 1e-6;
/// More rows than this is refused as a likely mistake (narrow --from/--to or lower --rate).
inline constexpr double kMaxSampleRows = 10'000'000;

/// Declares the `sample` subcommand and its options on `app`, writing into `options`. The
/// caller runs run_sample(options, ...) when the returned subcommand was given.
CLI::App* add_sample_subcommand(CLI::App& app, SampleOptions& options);

/// Validates the whole show (as `avar check` does, without a rig) and the options, then writes
/// the CSV: header `seconds,<channel>...`, one row per sample time t_i = from + i * step (rounded
/// to the nanosecond), from `from` up to and including `to` (when it falls on the grid). Each
/// column is the channel's curve at t_i as the curve defines it outside its keys: a looping show
/// is not wrapped. A layered show's columns are every channel its tracks and layers drive,
/// composed by playback::Sampler (a looping show wraps) over its tracks, else the rig's rest pose
/// (options.rig_path, whose channels must include the show's), else 0. With engine "device" (needs
/// the rig) each column is what the device engine outputs for the track at the grid's tick, in
/// channel units. Numbers are the shortest text that reads back to the same double. Returns
/// kExitOk, or kExitBadInput after one line on `err` naming the problem.
int run_sample(const SampleOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
