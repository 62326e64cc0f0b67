#include "avar/mocap_bake_command.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <ostream>

#include "avar/check_command.hpp"
#include "avar/config/retarget_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/config/mocap_bake.hpp"

namespace avar::app {

using config::bake_show;
using config::Baked;
using config::BakeReport;
using config::BakeSettings;
using config::load_motion_file;
using config::measure_fit;

CLI::App* add_mocap_bake_subcommand(CLI::App& mocap, MocapBakeOptions& o) {
  CLI::App* cmd =
      mocap.add_subcommand("bake", "Retarget a motion-capture file onto a rig through a map and write an editable show");
  cmd->add_option("file", o.mocap_path, "Motion-capture file (.bvh, .gltf, .glb)")->required();
  cmd->add_option("--map", o.map_path, "Retarget map (YAML: retarget: rotations, positions)")->required();
  cmd->add_option("--rig", o.rig_path, "Rig file the show is for")->required();
  cmd->add_option("--out", o.out_path, "Show file to write (YAML)")->required();
  cmd->add_option("--tolerance", o.tolerance,
                  "Largest difference of a channel's keys from the samples, channel units (default 0.25)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--position-tolerance", o.position_tolerance,
                  "Largest difference of an IK target's keys from the samples, metres (default 0.001)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--fps", o.fps, "Samples per second fitted (default: a BVH's own frame rate; glTF is sampled at 30)")
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_flag("--clamp", o.clamp, "Clamp samples outside a channel's limits (counted) instead of refusing the bake");
  cmd->add_flag(
      "--no-progress", [&o](std::int64_t) { o.progress = false; }, "Do not print progress lines");
  cmd->footer(
      "Every rotation binding becomes a track, every position binding a position target that inverse\n"
      "kinematics solves every tick. A sample outside its channel's limits refuses the bake (exit 2)\n"
      "unless --clamp. The written show is read back and checked as `avar check` does.\n"
      "Example:\n"
      "  avar mocap bake examples/mocap/nod.bvh --map examples/mocap/hello-head-map.yaml \\\n"
      "      --rig examples/rigs/hello-head.yaml --out nod.yaml");
  return cmd;
}

int run_mocap_bake(const MocapBakeOptions& o, std::ostream& out, std::ostream& err) {
  try {
    const rig::Rig rig = config::load_rig_file(o.rig_path);
    const mocap::RetargetMap map = config::load_retarget_map(o.map_path, rig);
    const mocap::SkeletonAnimation animation = load_motion_file(o.mocap_path, o.fps.value_or(30));
    BakeSettings settings;
    settings.tolerance = o.tolerance;
    settings.position_tolerance = o.position_tolerance;
    settings.sample_rate_hz = o.fps.value_or(0);
    settings.clamp = o.clamp;
    Baked baked = bake_show(animation, map, rig, settings, std::filesystem::path(o.mocap_path).stem().string(),
                            o.progress ? &err : nullptr);
    const config::ShowCheck check = config::check_show_against_rig(baked.show, rig);
    for (const auto& e : check.errors) err << "error: " << e.to_string() << '\n';
    if (!check.ok()) {
      err << check.errors.size() << " error(s): the baked show cannot play on this rig; nothing written\n";
      return kExitBadInput;
    }
    config::write_show_file(o.out_path, baked.show,
                            "written by avar mocap bake from " + o.mocap_path + " through " + o.map_path + "; edit freely");
    const playback::Show written = config::load_show_file(o.out_path);
    measure_fit(written, baked.samples, baked.report);
    for (const BakeReport::Channel& c : baked.report.channels) {
      out << c.name << ": " << c.samples << " samples in, " << c.keys << " keys out, max error " << format_number(c.max_error)
          << ' ' << c.unit << " (tolerance " << format_number(c.unit == "m" ? o.position_tolerance : o.tolerance) << ')';
      if (c.clamped > 0) out << ", " << c.clamped << " samples clamped into the limits";
      out << '\n';
    }
    out << "wrote " << o.out_path << " (" << written.tracks.size() << " tracks, " << written.targets.size() << " IK targets, "
        << format_number(written.duration) << " s)\n";
    return run_check(o.out_path, o.rig_path, "", out, err);
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
