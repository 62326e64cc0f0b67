#include "avar/jaw_command.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <ostream>

#include "avar/check_command.hpp"
#include "avar/config/jaw_track.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/option_error.hpp"

namespace avar::app {
namespace {

/// "LO-HI" in Hz.
std::pair<double, double> parse_band(const std::string& text) {
  const auto dash = text.find('-');
  const auto number = [&](std::string_view part, double& value) {
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    return ec == std::errc() && ptr == part.data() + part.size() && std::isfinite(value);
  };
  double lo = 0, hi = 0;
  if (dash == std::string::npos || !number(std::string_view(text).substr(0, dash), lo) ||
      !number(std::string_view(text).substr(dash + 1), hi) || !(lo > 0) || !(hi > lo))
    throw option_error("--band", "found '" + text + "'; expected LO-HI in Hz with 0 < LO < HI, e.g. 300-3000");
  return {lo, hi};
}

}  // namespace

CLI::App* add_jaw_subcommand(CLI::App& app, JawCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("jaw", "Make a talking figure's jaw track from a voice recording (WAV, FLAC, OGG)");
  cmd->add_option("audio", o.audio_path, "Sound file (any rate; channels are mixed down to mono)")->required();
  cmd->add_option("--rig", o.rig_path, "Rig file: the jaw channel's range and limits")->required();
  cmd->add_option("--channel", o.channel, "The jaw's channel in the rig (default jaw)");
  cmd->add_option("--out", o.out_path, "Show file to write (YAML, one track)")->required();
  cmd->add_option("--gate", o.gate_db,
                  "Speech-band level in dBFS that opens the mouth (default -40); quieter sound never moves it");
  cmd->add_option("--hysteresis", o.hysteresis_db, "The gate closes this many dB below --gate (default 6)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--full", o.full_db, "Level in dBFS at which the mouth is fully open (default -12), above --gate");
  cmd->add_option("--attack", o.attack_ms, "Opening time constant in ms (default 25)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--release", o.release_ms, "Closing time constant in ms (default 80)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--band", o.band, "Speech band LO-HI in Hz (default 300-3000)");
  cmd->add_option("--lead", o.lead_ms,
                  "Move this many ms before the sound (default: the channel's time to half open at its speed and "
                  "acceleration limits)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--curve", o.curve, "Exponent of the opening (default 0.7; below 1 opens more on quiet syllables)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--closed", o.closed, "Channel value of the closed mouth (default: the channel's rest)");
  cmd->add_option("--open", o.open,
                  "Channel value of the open mouth (default: the limit farther from rest, inside its soft margin)");
  cmd->add_option("--tolerance", o.tolerance, "Fitting tolerance in channel units (default 1% of the travel)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--verbose", o.verbose, "List every segment's share of the channel's limits, not only the worst ones");
  cmd->footer(
      "The speech band of the voice (zero-phase band-pass) gives an RMS envelope at 100 frames/s; a gate\n"
      "with hysteresis keeps the mouth exactly closed in silence and under noise; attack and release\n"
      "smooth it; the curve maps it onto [closed, open]; the lead makes the motion come earlier than the\n"
      "sound by the servo's lag. The frames are fitted with few Bezier keys (like avar fit), written as\n"
      "a show as long as the audio, and checked against the rig (like avar check): a count of segments\n"
      "and the worst, then the segments over a limit or within 10 % of one (--verbose: every segment).\n"
      "Example:\n"
      "  espeak-ng -w hello.wav \"Good evening, and welcome\"\n"
      "  avar jaw hello.wav --rig examples/rigs/talking-skull.yaml --out hello-jaw.yaml\n"
      "  avar play hello-jaw.yaml --rig examples/rigs/talking-skull.yaml --fast --plot jaw.svg");
  return cmd;
}

int run_jaw(const JawCommandOptions& options, std::ostream& out, std::ostream& err) {
  try {
    const rig::Rig rig = config::load_rig_file(options.rig_path);
    const auto index = rig.find_channel(options.channel);
    if (!index)
      throw option_error("--channel",
                         "rig '" + rig.name + "' has no channel '" + options.channel + "'; expected one of its channels");
    const rig::ChannelSpec& channel = rig.channels[*index];
    if (channel.digital())
      throw option_error("--channel", "channel '" + channel.name + "' is digital (on/off); expected an analog channel for a jaw");
    playback::JawOptions jaw;
    jaw.closed = options.closed.value_or(channel.rest);
    const double low = channel.min + channel.soft_margin, high = channel.max - channel.soft_margin;
    jaw.open = options.open.value_or(std::abs(high - channel.rest) >= std::abs(channel.rest - low) ? high : low);
    for (const auto& [name, value] : {std::pair{"--closed", jaw.closed}, std::pair{"--open", jaw.open}})
      if (value < channel.min || value > channel.max)
        throw option_error(name, "found " + format_number(value) + " " + channel.unit + "; expected within channel '" +
                                     channel.name + "' limits [" + format_number(channel.min) + ", " +
                                     format_number(channel.max) + "]");
    if (jaw.open == jaw.closed) throw option_error("--open", "the open mouth equals the closed one; expected a different value");
    if (options.gate_db) jaw.gate_db = *options.gate_db;
    if (options.full_db) jaw.full_db = *options.full_db;
    if (options.hysteresis_db) jaw.hysteresis_db = *options.hysteresis_db;
    if (options.attack_ms) jaw.attack_s = *options.attack_ms / 1000;
    if (options.release_ms) jaw.release_s = *options.release_ms / 1000;
    if (options.curve) jaw.curve = *options.curve;
    if (options.band) std::tie(jaw.band_low_hz, jaw.band_high_hz) = parse_band(*options.band);
    if (!(jaw.full_db > jaw.gate_db))
      throw option_error("--full", "found " + format_number(jaw.full_db) + " dBFS; expected above the gate (" +
                                       format_number(jaw.gate_db) + " dBFS)");
    const bool stated_lead = options.lead_ms.has_value();
    jaw.lead_s = stated_lead ? *options.lead_ms / 1000
                             : playback::time_to_half_open(jaw.open - jaw.closed, channel.max_velocity, channel.max_acceleration);
    const double tolerance = options.tolerance.value_or(config::default_jaw_tolerance(jaw));

    const config::JawTrack result =
        config::jaw_track_from_audio(options.audio_path, channel.name, jaw, tolerance, {options.audio_path, 0, 0});
    const auto& m = result.motion;
    const auto speaking = std::count_if(m.values.begin(), m.values.end(), [&](double v) { return v != jaw.closed; });
    out << "read " << options.audio_path << ": " << format_number(result.audio_duration_s) << " s, " << m.times.size()
        << " envelope frames, mouth open in " << speaking << " of them\n";
    out << channel.name << ": closed " << format_number(jaw.closed) << ", open " << format_number(jaw.open) << " " << channel.unit
        << ", gate " << format_number(jaw.gate_db) << " dBFS, lead " << format_number(jaw.lead_s * 1000) << " ms"
        << (stated_lead ? "" : " (time to half open at the channel's speed and acceleration limits)") << '\n';
    playback::Show show;
    show.name = std::filesystem::path(options.audio_path).stem().string();
    show.duration = std::max(result.audio_duration_s, m.times.back() + 1 / jaw.frame_rate_hz);
    show.tracks.push_back(result.track);
    config::write_show_file(options.out_path, show, "written by avar jaw from " + options.audio_path);
    out << "fitted " << result.track.raw.keys.size() << " keys within " << format_number(tolerance) << " " << channel.unit
        << "; wrote " << options.out_path << " (" << format_number(show.duration) << " s)\n";
    return run_check(options.out_path, options.rig_path, "", out, err,
                     options.verbose ? SegmentListing::every : SegmentListing::summary);
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
