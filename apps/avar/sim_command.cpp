#include "avar/sim_command.hpp"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "avar/assembly/sim_offer.hpp"
#include "avar/exit_codes.hpp"
#include "avar/interrupts.hpp"
#include "avar/sim/pty_device_host.hpp"

namespace avar::app {
namespace {

/// Serves `device` on a pseudo-terminal until SIGINT or SIGTERM. `state` describes the device
/// for the status line (called with the device locked).
int serve_on_pty(sim::ByteDevice& device, const std::string& description, const std::function<std::string()>& state,
                 std::ostream& out, std::ostream& err) {
  // Blocked before the host thread starts, so that it inherits the mask.
  const StopSignals stop;
  sim::PtyDeviceHost host(device, sim::PtyDeviceHost::Clock::wall);
  out << host.slave_path() << std::endl;
  err << description << " on " << host.slave_path() << "; Ctrl-C to stop\n";

  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  std::uint64_t last_bytes = 0;
  // The host serves on its own thread; this loop only reports, twice a second, until a signal.
  while (!stop.wait(500)) {
    const std::uint64_t bytes = host.with_device([&](sim::ByteDevice& d) { return d.bytes_received(); });
    if (terminal && bytes != last_bytes) {
      const std::string line = host.with_device([&](sim::ByteDevice&) { return state(); });
      err << '\r' << bytes << " bytes received; " << line << "\033[K" << std::flush;
    }
    last_bytes = bytes;
  }
  if (terminal) err << '\n';
  const std::uint64_t total = host.with_device([&](sim::ByteDevice& d) { return d.bytes_received(); });
  err << description << " stopped after " << total << " bytes\n";
  return kExitOk;
}

/// Serves a node on loopback until SIGINT or SIGTERM, taking its datagrams as they come.
int serve_on_udp(sim::SimDmxNode& node, const std::string& description, const std::function<std::string()>& state,
                 std::ostream& out, std::ostream& err) {
  const StopSignals stop;
  out << node.endpoint() << std::endl;
  err << description << " on " << node.endpoint() << "; Ctrl-C to stop\n";
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  std::uint64_t last = 0;
  // Each pass waits up to half a second for datagrams, then looks for a signal without waiting.
  while (!stop.wait(0)) {
    node.receive_until(node.counters().bytes + 1, std::chrono::milliseconds(500));
    if (terminal && node.counters().bytes != last)
      err << '\r' << node.counters().bytes << " bytes received; " << state() << "\033[K" << std::flush;
    last = node.counters().bytes;
  }
  if (terminal) err << '\n';
  err << description << " stopped after " << node.counters().bytes << " bytes\n";
  return kExitOk;
}

/// The text after `avar sim`'s own options.
std::string sim_footer() {
  return "A simulated device speaks its protocol byte for byte, as the hardware does, so any program can drive it: avar "
         "itself (avar play SHOW --rig RIG --port PATH), a vendor's tool, a script. Serial devices are served on a "
         "pseudo-terminal, network ones on UDP at 127.0.0.1; the first line on stdout is where (a path or HOST:PORT), "
         "status goes to stderr, Ctrl-C stops it. `avar sim NAME --help` tells what each device is, its options and an "
         "example.\n"
         "\nExample:\n  avar sim maestro --channels 12        # prints /dev/pts/N\n"
         "  avar play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml --port /dev/pts/N\n";
}

}  // namespace

void add_sim_subcommands(CLI::App& app, SimCommands& commands) {
  commands.sim = app.add_subcommand("sim", "Run a simulated device (servo controller, bus, drive, DMX node) for other programs");
  commands.sim->require_subcommand(1);
  commands.sim->footer(sim_footer());
  for (const assembly::SimOffer* offer : assembly::sim_offers()) {
    SimCommands::Device& d = commands.devices.emplace_back();
    d.offer = offer;
    d.command = commands.sim->add_subcommand(offer->name, offer->summary);
    if (offer->alias) d.command->alias(offer->alias);
    d.command->footer(assembly::sim_offer_help(*offer));
    if (offer->transport == assembly::SimTransport::pty)
      d.command->add_flag("--pty", d.pty, "Serve on a pseudo-terminal (the default: a serial device is served there)");
    for (const assembly::SimOption& o : offer->options) {
      const std::string flag = "--" + std::string(o.name);
      if (o.flag) {
        d.command->add_flag(flag, d.flags[o.name], o.help);
      } else {
        std::string& value = d.values[o.name];
        value = o.default_value;
        d.command->add_option(flag, value, std::string(o.help) + " (default " + o.default_value + ")");
      }
    }
  }
}

int run_sim(const SimCommands& commands, std::ostream& out, std::ostream& err) {
  for (const SimCommands::Device& d : commands.devices) {
    if (!*d.command) continue;
    const assembly::SimOffer& offer = *d.offer;
    if (!offer.make) {
      err << "error: a simulated " << offer.name << " device is served " << assembly::to_string(offer.transport) << ".\n"
          << offer.description << "\nExample:\n"
          << offer.example << "\n";
      return kExitBadInput;
    }
    assembly::SimValues values;
    for (const auto& [name, value] : d.values) values.set(name, value);
    for (const auto& [name, given] : d.flags) values.set(name, given ? "true" : "");
    assembly::ServedDevice device;
    try {
      device = offer.make(values);
    } catch (const assembly::SimOptionError& e) {
      err << "error: " << e.what() << "\n";
      return kExitBadInput;
    }
    if (device.network_node) return serve_on_udp(*device.network_node, device.description, device.state, out, err);
    return serve_on_pty(*device.device, device.description, device.state, out, err);
  }
  return kExitBadInput;
}

}  // namespace avar::app
