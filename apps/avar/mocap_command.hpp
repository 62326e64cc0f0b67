#pragma once
// `avar mocap info|joints FILE`: what a motion-capture file (BVH) holds, and the world position
// of every joint per frame as CSV, to inspect, plot or compare with other tools. Moves nothing.

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace avar::app {

struct MocapOptions {
  std::string path;                ///< the motion-capture file
  std::optional<double> fps;       ///< joints: sample rate for formats without frames of their own
  std::optional<std::string> out;  ///< joints: CSV file (default standard output)
};

struct MocapCommands {
  CLI::App* mocap = nullptr;
  CLI::App* info = nullptr;
  CLI::App* joints = nullptr;
};

/// Declares `mocap` with its `info` and `joints` subcommands on `app`, writing into `options`.
MocapCommands add_mocap_subcommands(CLI::App& app, MocapOptions& options);

/// Runs the mocap subcommand that was given. Returns kExitOk, or kExitBadInput after one line on
/// `err` ("error: file:line:col: ...") for a file or option that is refused.
int run_mocap(const MocapCommands& commands, const MocapOptions& options, std::ostream& out, std::ostream& err);

/// `info`: the file's format, joint tree with channels, frame count, frame time, rate, duration.
int run_mocap_info(const MocapOptions& options, std::ostream& out, std::ostream& err);

/// `joints`: header `frame,joint,x,y,z`, then for every frame (0-based) and every joint in
/// hierarchy order (End Sites included, named <parent>_end) the world position of the joint's
/// origin, in the file's axes and units. Numbers are the shortest text that reads back exactly.
int run_mocap_joints(const MocapOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
