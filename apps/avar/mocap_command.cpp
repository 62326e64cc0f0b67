#include "avar/mocap_command.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <ostream>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "avar/exit_codes.hpp"
#include "avar/mocap/mocap_file.hpp"

namespace avar::app {
namespace {

struct MocapOptionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

mocap::SkeletonAnimation load_for_command(const MocapOptions& o) {
  mocap::MocapLoadOptions load;
  if (o.fps) {
    if (!std::isfinite(*o.fps) || *o.fps <= 0)
      throw MocapOptionError("expected --fps to be a number more than 0, found " + format_number(*o.fps));
    if (mocap::mocap_format(o.path) == mocap::MocapFormat::bvh)
      throw MocapOptionError("--fps applies to files without frames of their own; a BVH file's rows are its frames");
    load.sample_rate_hz = *o.fps;
  }
  return mocap::load_mocap_file(o.path, load);
}

void print_joint_tree(const mocap::SkeletonAnimation& a, std::ostream& out) {
  std::vector<std::size_t> depth(a.joints.size(), 0);
  for (std::size_t j = 0; j < a.joints.size(); ++j) {
    const auto parent = a.joints[j].parent;
    if (parent != mocap::kNoParent) depth[j] = depth[static_cast<std::size_t>(parent)] + 1;
    out << std::string(2 * depth[j] + 2, ' ') << a.joints[j].name;
    if (a.joints[j].end_site) {
      out << "  (End Site)";
    } else if (a.channels.empty() || a.channels[j].empty()) {
      out << "  (no channels)";
    } else {
      out << "  [";
      for (std::size_t c = 0; c < a.channels[j].size(); ++c) out << (c ? " " : "") << a.channels[j][c];
      out << ']';
    }
    out << '\n';
  }
}

template <typename Body>
int run_guarded(std::ostream& err, Body body) {
  try {
    return body();
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
  } catch (const MocapOptionError& e) {
    err << "error: " << e.what() << '\n';
  }
  return kExitBadInput;
}

}  // namespace

MocapCommands add_mocap_subcommands(CLI::App& app, MocapOptions& o) {
  MocapCommands c;
  c.mocap = app.add_subcommand("mocap", "Inspect motion-capture files (BVH, glTF 2.0): their skeleton and joint positions");
  c.mocap->require_subcommand(1);
  c.mocap->footer(
      "Units and axes are the file's own: nothing is converted. BVH End Sites appear as joints named\n"
      "<parent>_end. Examples:\n"
      "  avar mocap info walk.bvh\n"
      "  avar mocap joints walk.bvh --out joints.csv\n"
      "  avar mocap joints wave.glb --fps 60 --out joints.csv");

  c.info = c.mocap->add_subcommand("info", "Print the joint tree with each joint's channels, frame count, rate and duration");
  c.info->add_option("file", o.path, "Motion-capture file (.bvh, .gltf or .glb), validated whole first")->required();
  c.info->footer(
      "Each line is a joint, indented under its parent, with the channels the file animates in file\n"
      "order (BVH rotations compose in that order, the first outermost). Example:\n"
      "  avar mocap info walk.bvh");

  c.joints = c.mocap->add_subcommand("joints", "Write the world position of every joint, every frame, as CSV");
  c.joints->add_option("file", o.path, "Motion-capture file (.bvh, .gltf or .glb), validated whole first")->required();
  c.joints->add_option("--fps", o.fps,
                       "glTF: samples per second, at i / F s over the animation (default 30); BVH files keep their own frames");
  c.joints->add_option("--out", o.out, "Write the CSV to this file instead of standard output");
  c.joints->footer(
      "Output: a header `frame,joint,x,y,z`, then one row per frame (0-based: BVH the file's frames, glTF\n"
      "samples at i / --fps s) and joint (hierarchy order, BVH End Sites as <parent>_end): the joint\n"
      "origin's position in the file's own axes and units (forward kinematics). Examples:\n"
      "  avar mocap joints walk.bvh --out joints.csv\n"
      "  avar mocap joints wave.glb --fps 60 --out joints.csv");
  return c;
}

int run_mocap_info(const MocapOptions& o, std::ostream& out, std::ostream& err) {
  return run_guarded(err, [&] {
    const mocap::SkeletonAnimation a = load_for_command(o);
    std::size_t end_sites = 0;
    for (const auto& joint : a.joints) end_sites += joint.end_site ? 1 : 0;
    out << o.path << ": " << mocap::to_string(mocap::mocap_format(o.path)) << '\n' << "joints: " << a.joints.size() - end_sites;
    if (end_sites) out << " (+" << end_sites << " End Sites)";
    out << '\n';
    print_joint_tree(a, out);
    out << "frames: " << a.frame_count() << '\n'
        << "frame time: " << format_number(a.frame_time) << " s (" << format_number(1.0 / a.frame_time) << " fps)\n"
        << "duration: " << format_number(a.duration()) << " s\n";
    return kExitOk;
  });
}

int run_mocap_joints(const MocapOptions& o, std::ostream& out, std::ostream& err) {
  return run_guarded(err, [&] {
    const mocap::SkeletonAnimation a = load_for_command(o);
    std::ofstream file;
    if (o.out) {
      file.open(*o.out);
      if (!file) throw MocapOptionError("cannot write '" + *o.out + "'; expected a writable path for --out");
    }
    std::ostream& csv = o.out ? file : out;
    csv << "frame,joint,x,y,z\n";
    std::vector<Eigen::Affine3d> world;
    std::string line;
    for (std::size_t f = 0; f < a.frame_count(); ++f) {
      mocap::forward_kinematics(a, a.frames[f], world);
      for (std::size_t j = 0; j < a.joints.size(); ++j) {
        line = std::to_string(f) + ',' + a.joints[j].name;
        for (int k = 0; k < 3; ++k) {
          line += ',';
          append_round_trip(line, world[j].translation()[k]);
        }
        line += '\n';
        csv << line;
      }
    }
    if (o.out && !file.flush()) throw MocapOptionError("cannot write '" + *o.out + "' to its end");
    return kExitOk;
  });
}

int run_mocap(const MocapCommands& c, const MocapOptions& o, std::ostream& out, std::ostream& err) {
  if (*c.info) return run_mocap_info(o, out, err);
  if (*c.joints) return run_mocap_joints(o, out, err);
  return kExitBadInput;
}

}  // namespace avar::app
