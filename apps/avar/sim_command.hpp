#pragma once
// `avar sim NAME [options]`: a simulated device for other programs (or another avar) to drive.
// One subcommand per offer of the protocol registry (avar::assembly::sim_offers()): each
// protocol and each CAN drive protocol, with the options, help and transport its entry gives.

#include <iosfwd>
#include <list>
#include <map>
#include <string>

namespace CLI {
class App;
}

namespace avar::assembly {
struct SimOffer;
}

namespace avar::app {

struct SimCommands {
  struct Device {
    CLI::App* command = nullptr;
    const assembly::SimOffer* offer = nullptr;
    std::map<std::string, std::string> values;  ///< option name -> value as given (defaults filled in)
    std::map<std::string, bool> flags;          ///< flag name -> given
    bool pty = false;                           ///< --pty given (the default transport of a serial device)
  };
  CLI::App* sim = nullptr;
  std::list<Device> devices;  ///< a list: CLI11 writes into the maps through stable addresses
};

/// Declares `sim` and one subcommand per offer of the registry on `app`; `commands` must stay
/// where it is while `app` parses.
void add_sim_subcommands(CLI::App& app, SimCommands& commands);

/// Runs the subcommand given: makes its device, prints where it is served on `out` (one line,
/// nothing else, so scripts can read it: a pseudo-terminal's path or HOST:PORT), a status line on
/// `err`, and serves until SIGINT/SIGTERM. Returns the exit code (2 for a bad option, or for a
/// device served only inside the avar that drives it).
int run_sim(const SimCommands& commands, std::ostream& out, std::ostream& err);

}  // namespace avar::app
