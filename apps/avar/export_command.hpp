#pragma once
// `avar export SHOW... --rig RIG --target TARGET --out DIR`: the shows and the rig's figure as an
// Arduino / PlatformIO library that plays them on a microcontroller (avar/device/project_export.hpp);
// `avar export --stream --rig RIG ...`: the board of the rig's avar-device link, which plays what
// avar streams to it.

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace avar::app {

struct ExportOptions {
  std::vector<std::string> show_paths;
  std::string rig_path;
  std::string target;
  std::string out_dir;
  std::string name;     ///< the library's name; "" for avar_<rig>
  std::string boot;     ///< a show's name or number (1-based) played at power-up
  std::string idle;     ///< a show played whenever nothing else plays
  std::string button;   ///< PIN or PIN:SHOW
  long baud = 0;        ///< the serial commands'; 0: not given (115200)
  bool verify = false;  ///< build for the host and the target, run under its emulator, compare
  bool stream = false;  ///< a streaming board (no shows)
};

CLI::App* add_export_subcommand(CLI::App& app, ExportOptions& options);

/// Loads and checks the rig and every show whole, builds the project (refusing, with the budget,
/// one that does not fit the target), writes it and prints what it wrote and the budget. Returns
/// kExitOk, or kExitBadInput after one message on `err`; nothing is written on an error. With
/// verify, then builds and runs it on the host and under the target's emulator and prints
/// "TARGET: N samples, M mismatches": kExitFault on a mismatch, kExitBadInput when a tool is
/// missing or a build fails.
int run_export(const ExportOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
