#include "avar/sample_command.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <ostream>
#include <stdexcept>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/playback/runtime/sampler.hpp"
#include "avar/core/format.hpp"
#include "avar/device/image_sampler.hpp"
#include "avar/device/show_export.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

/// A bad command-line value: the message says what was found and what was expected.
struct OptionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Grid {
  double from = 0;
  double step = 0;
  std::size_t rows = 0;
  double to = 0;
};

void expect_finite(const std::optional<double>& value, const char* option) {
  if (value && !std::isfinite(*value)) throw OptionError(std::string("expected ") + option + " to be a finite number, found " + format_number(*value));
}

Grid grid_for(const SampleOptions& o, double duration) {
  expect_finite(o.rate_hz, "--rate");
  expect_finite(o.step_s, "--step");
  expect_finite(o.from_s, "--from");
  expect_finite(o.to_s, "--to");
  if (o.rate_hz && o.step_s) throw OptionError("--rate and --step both given; expected one of them (--step = 1 / --rate)");
  if (o.rate_hz && *o.rate_hz <= 0) throw OptionError("expected --rate to be more than 0 Hz, found " + format_number(*o.rate_hz));
  if (o.step_s && *o.step_s <= 0) throw OptionError("expected --step to be more than 0 s, found " + format_number(*o.step_s));
  Grid g;
  g.step = o.step_s ? *o.step_s : 1.0 / o.rate_hz.value_or(kDefaultSampleRateHz);
  if (g.step < kMinSampleStepS)
    throw OptionError("expected samples at least " + format_number(kMinSampleStepS) + " s apart (--rate up to " +
                      format_number(1 / kMinSampleStepS) + " Hz), found " + format_number(g.step) + " s");
  g.from = o.from_s.value_or(0.0);
  g.to = o.to_s.value_or(duration);
  if (!(g.from < g.to))
    throw OptionError("expected --from (" + format_number(g.from) + " s) to be before --to (" + format_number(g.to) +
                      " s)" + (o.to_s ? "" : ", the show's duration"));
  // The tolerance keeps `to` when rounding puts it a hair past the last whole step.
  const double intervals = std::floor((g.to - g.from) / g.step + 1e-9);
  if (intervals + 1 > kMaxSampleRows)
    throw OptionError("the range " + format_number(g.from) + " to " + format_number(g.to) + " s at " + format_number(g.step) +
                      " s per sample makes " + format_number(intervals + 1) + " rows; expected at most " +
                      format_number(kMaxSampleRows) + " (lower --rate or narrow --from/--to)");
  g.rows = static_cast<std::size_t>(intervals) + 1;
  return g;
}

/// from + i * step on a nanosecond grid, so 0.1 * 3 prints as 0.3 and the printed time is the
/// evaluated time.
double sample_time(const Grid& g, std::size_t i) {
  const double t = g.from + static_cast<double>(i) * g.step;
  return std::round(t * 1e9) / 1e9;
}

/// The channels the show drives, in file order: its tracks, then those its layers touch.
std::vector<std::string> driven_channels(const playback::Show& show) {
  std::vector<std::string> names;
  const auto add = [&](const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  };
  for (const auto& track : show.tracks) add(track.channel);
  for (const auto& layer : show.layers)
    for (const auto& placement : layer.placements)
      for (const auto& track : show.clips[placement.clip].tracks)
        if (layer.touches(track.channel)) add(track.channel);
  for (const auto& layer : show.layers)
    for (const std::string& name : playback::behaviour_channels(layer)) add(name);
  return names;
}

/// Indices into `available` of the columns to print, in column order.
std::vector<std::size_t> columns_for(const std::vector<std::string>& available, const std::vector<std::string>& channels) {
  std::vector<std::size_t> columns;
  if (channels.empty()) {
    for (std::size_t i = 0; i < available.size(); ++i) columns.push_back(i);
    return columns;
  }
  for (const auto& name : channels) {
    const auto found = std::find(available.begin(), available.end(), name);
    if (found == available.end()) {
      std::string list;
      for (const auto& a : available) list += (list.empty() ? "" : ", ") + a;
      throw OptionError("unknown channel '" + name + "' in --channels; the show has: " + list);
    }
    const auto index = static_cast<std::size_t>(found - available.begin());
    if (std::find(columns.begin(), columns.end(), index) != columns.end())
      throw OptionError("channel '" + name + "' is listed twice in --channels; expected each once");
    columns.push_back(index);
  }
  return columns;
}

/// Writes the header and one row per grid time; `values(t, row)` fills one value per column.
template <typename Values>
void write_csv(const std::vector<std::string>& header, const Grid& grid, std::ostream& out, Values values) {
  std::string line = "seconds";
  for (const auto& name : header) line += "," + name;
  out << line << '\n';
  std::vector<double> row(header.size());
  for (std::size_t i = 0; i < grid.rows; ++i) {
    const double t = sample_time(grid, i);
    values(t, row);
    line.clear();
    append_round_trip(line, t);
    for (double v : row) {
      line += ',';
      append_round_trip(line, v);
    }
    line += '\n';
    out << line;
  }
}

/// The CSV of a show: a plain show's curves evaluated directly (a looping show is not wrapped);
/// a layered show composed as it plays, on the rig's channels and rest pose when a rig is given,
/// else over 0 for channels without a show track.
void write_show_csv(const playback::Show& show, const std::optional<rig::Rig>& rig, const Grid& grid,
                    const std::vector<std::string>& wanted, std::ostream& out) {
  const std::vector<std::string> available = driven_channels(show);
  const std::vector<std::size_t> columns = columns_for(available, wanted);
  std::vector<std::string> header;
  for (std::size_t c : columns) header.push_back(available[c]);
  if (!show.layered()) {
    std::vector<playback::CurveCursor> cursors(columns.size());
    write_csv(header, grid, out, [&](double t, std::vector<double>& row) {
      for (std::size_t c = 0; c < columns.size(); ++c) row[c] = show.tracks[columns[c]].curve.evaluate(t, cursors[c]);
    });
    return;
  }
  std::vector<std::string> frame_channels = available;
  std::vector<double> defaults(available.size(), 0.0);
  if (rig) {
    frame_channels.clear();
    for (const auto& c : rig->channels) frame_channels.push_back(c.name);
    defaults = rig->rest_frame();
  }
  std::vector<std::size_t> slot;
  for (const auto& name : header)
    slot.push_back(static_cast<std::size_t>(std::find(frame_channels.begin(), frame_channels.end(), name) - frame_channels.begin()));
  playback::Sampler sampler(show, frame_channels, defaults);
  std::vector<double> frame(frame_channels.size());
  write_csv(header, grid, out, [&](double t, std::vector<double>& row) {
    sampler.sample(t, frame);
    for (std::size_t c = 0; c < slot.size(); ++c) row[c] = frame[slot[c]];
  });
}

/// The CSV of the device engine's host build: the show's tracks encoded as a device image over
/// the rig's channel ranges (a tick rate on which the grid and every key fall on whole ticks),
/// sampled at each grid time's tick and mapped back to channel units.
void write_device_csv(const playback::Show& show, const rig::Rig& rig, const Grid& grid, const std::vector<std::string>& wanted,
                      std::ostream& out) {
  const std::vector<std::string> available = driven_channels(show);
  const std::vector<std::size_t> columns = columns_for(available, wanted);
  std::vector<device::ImageChannel> channels;
  std::vector<std::string> header;
  for (std::size_t c : columns) {
    const rig::ChannelSpec& channel = rig.channels[rig.find_channel(available[c]).value()];
    channels.push_back({available[c], {channel.min, channel.max}});
    header.push_back(available[c]);
  }
  device::ImageOptions options;
  options.on_grid = {grid.step, grid.from};
  device::ImageSampler sampler(device::encode_show_image(show, channels, options).bytes);
  const double tps = sampler.ticks_per_second();
  write_csv(header, grid, out, [&](double t, std::vector<double>& row) {
    const auto tick = static_cast<std::int32_t>(std::llround(t * tps));
    for (std::size_t c = 0; c < channels.size(); ++c) row[c] = channels[c].range.to_channel(sampler.output(c, tick));
  });
}

/// The rig of --rig, checked against the show (a channel it lacks is refused with its place),
/// with the show's behaviour layers bound to it. Without --rig a behaviour layer is refused: its
/// generators need the rig's channels and limits.
std::optional<rig::Rig> rig_for(const SampleOptions& o, playback::Show& show) {
  if (!o.rig_path) {
    for (const playback::Layer& layer : show.layers)
      if (layer.behaviour)
        throw InputError(layer.behaviour->where, "layer '" + layer.name +
                                                     "' has behaviour, whose generators need the rig's channels and limits; "
                                                     "expected --rig RIG");
    return std::nullopt;
  }
  rig::Rig rig = config::load_rig_file(*o.rig_path);
  const config::ShowCheck check = config::check_show_against_rig(show, rig);
  if (!check.ok()) throw InputError(check.errors.front().where, check.errors.front().message);
  config::bind_show_behaviour(show, rig);
  return rig;
}

}  // namespace

CLI::App* add_sample_subcommand(CLI::App& app, SampleOptions& o) {
  CLI::App* cmd = app.add_subcommand("sample", "Write a show's curves, evaluated on a time grid, as CSV (needs no rig)");
  cmd->add_option("show", o.show_path, "Show file (validated whole first, as `avar check` does)")->required();
  CLI::Option* rate = cmd->add_option("--rate", o.rate_hz, "Samples per second (default 100)");
  CLI::Option* step = cmd->add_option("--step", o.step_s, "Seconds between samples, instead of --rate");
  rate->excludes(step);
  cmd->add_option("--from", o.from_s, "First sample time in seconds (default 0; may be negative, before the show)");
  cmd->add_option("--to", o.to_s, "Last sample time in seconds (default the show's duration; may lie past it)");
  cmd->add_option("--channels", o.channels, "Only these channels, in this order, comma-separated (default: all, in file order)")
      ->delimiter(',');
  cmd->add_option("--out", o.out_path, "Write the CSV to this file instead of standard output");
  cmd->add_option("--rig", o.rig_path,
                  "Rig file: a layered show is composed over the rig's rest pose (default: over 0 where no show track drives)");
  cmd->add_option(
         "--engine", o.engine,
         "double (avar's reference engine, the default) or device (the microcontroller engine's host build; needs --rig)")
      ->check(CLI::IsMember({"double", "device"}));
  cmd->footer(
      "Output: a header `seconds,<channel>,...`, then one row per sample time from --from to --to\n"
      "(inclusive when it falls on the grid). Each curve is evaluated as it is defined outside its keys too\n"
      "(held or extrapolated); a looping show is not wrapped. Numbers read back exactly.\n"
      "A show with layers of clips prints every channel its tracks and layers drive, composed as it plays\n"
      "(a looping one wraps); under the layers lie its tracks, else the --rig rest pose, else 0.\n"
      "Behaviour layers (idle generators in the show) need --rig: their channels and limits are the rig's.\n"
      "--engine device samples the integer engine that runs on a microcontroller (avar export): the show's\n"
      "tracks as 16-bit outputs over each rig channel's min..max, printed in channel units, within one\n"
      "output unit of the double engine; a grid time falls on the device's tick (chosen so that it does).\n"
      "Examples:\n"
      "  avar sample examples/shows/hello-head.yaml --rate 50 > hello-head.csv\n"
      "      every channel at 50 Hz over the whole show\n"
      "  avar sample SHOW --step 0.01 --from -1 --to 13 --channels neck_pan,jaw\n"
      "      two channels every 10 ms, one second either side of the show\n"
      "  avar sample before.yaml --out a.csv && avar sample after.yaml --out b.csv && diff a.csv b.csv\n"
      "      see exactly where two versions of a show differ\n"
      "  avar sample SHOW --rig RIG --engine device --out device.csv\n"
      "      what the show does on a microcontroller, to compare with the double engine's CSV");
  return cmd;
}

int run_sample(const SampleOptions& options, std::ostream& out, std::ostream& err) {
  try {
    playback::Show show = config::load_show_file(options.show_path);
    const Grid grid = grid_for(options, show.duration);
    const bool device_engine = options.engine == "device";
    if (device_engine && !options.rig_path)
      throw OptionError("--engine device needs --rig RIG: the device engine's output is 16 bits over each channel's min..max");
    const std::optional<rig::Rig> rig = rig_for(options, show);
    const auto write = [&](std::ostream& stream) {
      if (device_engine) {
        write_device_csv(show, *rig, grid, options.channels, stream);
      } else {
        write_show_csv(show, rig, grid, options.channels, stream);
      }
    };
    if (!options.out_path) {
      write(out);
      return kExitOk;
    }
    std::ofstream file(*options.out_path);
    if (!file) throw OptionError("cannot write --out " + *options.out_path + "; expected a writable file path");
    write(file);
    file.close();
    if (!file) throw OptionError("writing " + *options.out_path + " failed; expected a writable file path with free space");
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
  } catch (const OptionError& e) {
    err << "error: " << e.what() << '\n';
  }
  return kExitBadInput;
}

}  // namespace avar::app
