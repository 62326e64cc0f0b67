#pragma once
// `avar mocap bake FILE --map MAP.yaml --rig RIG --out SHOW.yaml`: a motion-capture file
// retargeted onto a rig through a map and written as an editable show (few Bezier keys per
// channel and per IK-target axis, within the tolerances), read back and checked against the rig
// as `avar check` does.

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace avar::app {

struct MocapBakeOptions {
  std::string mocap_path;
  std::string map_path;
  std::string rig_path;
  std::string out_path;
  double tolerance = 0.25;            ///< channel units
  double position_tolerance = 0.001;  ///< metres
  std::optional<double> fps;          ///< sample rate; default the file's frame rate
  bool clamp = false;
  bool progress = true;
};

/// Declares `bake` under the `mocap` subcommand, writing into `options`.
CLI::App* add_mocap_bake_subcommand(CLI::App& mocap, MocapBakeOptions& options);

/// Loads the rig, the map (checked against the rig) and the mocap file (its joints checked
/// against the map), bakes (mocap_bake.hpp), writes the show, loads it back and checks it: per
/// channel samples in, keys out and largest error of the written show; errors of the show check
/// and every feasibility finding (speed, acceleration) as `avar check` lists them. Returns
/// kExitOk, or kExitBadInput after "error: file:line:col: ..." lines (a bad file, a sample
/// outside its channel's limits without --clamp, a show the rig refuses).
int run_mocap_bake(const MocapBakeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
