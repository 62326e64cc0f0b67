#include "avar/visemes_command.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <ostream>

#include "avar/check_command.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/config/viseme_cues.hpp"
#include "avar/config/viseme_tracks.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {

CLI::App* add_visemes_subcommand(CLI::App& app, VisemesCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("visemes", "Make lip-sync tracks from mouth cues (Rhubarb TSV/JSON, Papagayo/Moho .dat)");
  cmd->add_option("cues", o.cues_path, "Mouth-cue file: Rhubarb Lip Sync TSV or JSON, or a Papagayo/Moho switch file")
      ->required();
  cmd->add_option("--rig", o.rig_path, "Rig file with a visemes: table (mouth shape -> pose of its channels)")->required();
  cmd->add_option("--out", o.out_path, "Show file to write (YAML, one track per posed channel)")->required();
  cmd->add_option("--fps", o.fps, "Frames per second of a Moho switch file (default 24)")->check(CLI::PositiveNumber);
  cmd->add_option("--rise", o.rise_ms, "Anticipation: time constant in ms of a shape's influence before it (default 50)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--decay", o.decay_ms, "Carry-over: time constant in ms of a shape's influence after it (default 50)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--tolerance", o.tolerance, "Fitting tolerance in channel units (default 1% of each channel's pose span)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--duration", o.duration_s, "Show duration in seconds (default: the last cue + 0.5 s)")
      ->check(CLI::PositiveNumber);
  cmd->footer(
      "Each cue's pose rises before it and decays after it (Cohen-Massaro dominance); every channel is\n"
      "the dominance-weighted average of the poses, so it never leaves the range the poses span.\n"
      "Examples:\n"
      "  rhubarb -f tsv voice.wav -o voice.tsv\n"
      "  avar visemes voice.tsv --rig examples/rigs/talking-skull.yaml --out lips.yaml\n"
      "  avar visemes song.dat --fps 30 --rig RIG --out lips.yaml        (Papagayo / Moho switch file)");
  return cmd;
}

int run_visemes(const VisemesCommandOptions& options, std::ostream& out, std::ostream& err) {
  try {
    const rig::Rig rig = config::load_rig_file(options.rig_path);
    const auto table = config::load_rig_visemes(options.rig_path, rig);
    if (!table)
      throw InputError({options.rig_path, 1, 1},
                       "rig '" + rig.name +
                           "' has no visemes: table; expected a map of mouth shape to a pose, e.g. "
                           "visemes: {A: {jaw: 0, lip_upper: -5}, D: {jaw: 20, lip_upper: 5}, X: {jaw: 0, lip_upper: 0}}");
    const auto cues = config::read_viseme_cues(options.cues_path, options.fps, {"--fps", 0, 0});
    playback::CoarticulationOptions blend;
    if (options.rise_ms) blend.rise_s = *options.rise_ms / 1000;
    if (options.decay_ms) blend.decay_s = *options.decay_ms / 1000;
    playback::Show show;
    show.name = std::filesystem::path(options.cues_path).stem().string();
    show.duration = options.duration_s.value_or(cues.back().end + 0.5);
    show.tracks = config::viseme_tracks(cues, *table, blend, 0, show.duration, options.tolerance, {options.cues_path, 1, 1});
    out << "read " << options.cues_path << ": " << cues.size() << " mouth cues, " << format_number(cues.back().end) << " s; "
        << table->shapes.size() << " shapes posing " << table->channels.size() << " channels\n";
    for (const auto& track : show.tracks) out << track.channel << ": " << track.raw.keys.size() << " keys\n";
    config::write_show_file(options.out_path, show, "written by avar visemes from " + options.cues_path);
    out << "wrote " << options.out_path << " (" << format_number(show.duration) << " s)\n";
    return run_check(options.out_path, options.rig_path, "", out, err);
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
