#pragma once
// `avar studio --rig RIG [SHOW]`: the studio's server over the figure (simulated or real), for
// the studio's page or any program that speaks the studio protocol.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace avar::app {

struct StudioOptions {
  std::string rig_path;
  std::optional<std::string> show_path;  ///< the show to edit; a path that does not exist is a new show saved there
  bool simulate = false;                 ///< --sim
  std::optional<std::string> port;       ///< --port: the rig's single link's port
  std::optional<double> rate_hz;         ///< default: the rig's
  std::string listen = "127.0.0.1:0";    ///< --listen HOST:PORT
  bool open_browser = false;             ///< --open
  std::optional<std::string> page_dir;   ///< --page: the page's folder; default: the one built with avar
  std::vector<std::string> inputs;       ///< --input URIs: live controls (default: --inputs' devices)
  std::optional<std::string> inputs_path;  ///< --inputs: the mappings' file; default: the rig's own inputs:
};

/// Declares `avar studio` and its options on `app`.
CLI::App* add_studio_subcommand(CLI::App& app, StudioOptions& options);

/// Runs the studio until Ctrl-C, a client's stop or a fault; returns the exit code.
int run_studio(const StudioOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
