#include "avar/sim_command.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <ostream>
#include <string>

#include "avar/exit_codes.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_maestro.hpp"

namespace avar::app {
namespace {

/// Serves `device` on a pseudo-terminal until SIGINT or SIGTERM. `state` describes the device
/// for the status line (called with the device locked).
int serve_on_pty(sim::ByteDevice& device, const std::string& description, const std::function<std::string()>& state,
                 std::ostream& out, std::ostream& err) {
  // SIGINT and SIGTERM are blocked here (and so in the host thread, which inherits the mask)
  // and taken synchronously below: the report loop waits on them instead of sleeping.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &stop_signals, &previous);
  sim::PtyDeviceHost host(device, sim::PtyDeviceHost::Clock::wall);
  out << host.slave_path() << std::endl;
  err << description << " on " << host.slave_path() << "; Ctrl-C to stop\n";

  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  std::uint64_t last_bytes = 0;
  const timespec half_second{0, 500'000'000};
  // The host serves on its own thread; this loop only reports, twice a second, until a signal.
  while (sigtimedwait(&stop_signals, nullptr, &half_second) < 0) {
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
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return kExitOk;
}

}  // namespace

int run_sim_maestro(const SimMaestroOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) {
    err << "error: say where to serve: --pty (a pseudo-terminal)\n";
    return kExitBadInput;
  }
  sim::SimMaestroConfig config;
  config.channel_count = options.channels;
  config.device_number = static_cast<std::uint8_t>(options.device_number);
  config.crc = options.crc;
  sim::SimMaestro device(config);
  const std::string description = "simulated Maestro (" + std::to_string(options.channels) + " channels, device number " +
                                  std::to_string(options.device_number) + (options.crc ? ", CRC on" : "") + ")";
  return serve_on_pty(
      device, description,
      [&] {
        std::string line = "outputs (µs):";
        char value[16];
        for (int ch = 0; ch < options.channels && ch < 12; ++ch) {
          std::snprintf(value, sizeof value, " %.0f", device.output_pulse(ch) / 4.0);
          line += value;
        }
        return line;
      },
      out, err);
}

int run_sim_dynamixel(const SimDynamixelOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) {
    err << "error: say where to serve: --pty (a pseudo-terminal)\n";
    return kExitBadInput;
  }
  sim::SimDynamixelConfig config;
  std::string ids;
  for (int id : options.ids) {
    if (id < 0 || id > firmware_iface::dynamixel::kMaxId) {
      err << "error: --ids: " << id << " is not a Dynamixel ID; expected 0 to 252\n";
      return kExitBadInput;
    }
    for (const auto& s : config.servos)
      if (s.id == id) {
        err << "error: --ids: " << id << " is given twice; every servo on a bus needs its own ID\n";
        return kExitBadInput;
      }
    sim::SimDynamixelServo servo;
    servo.id = static_cast<std::uint8_t>(id);
    config.servos.push_back(servo);
    ids += (ids.empty() ? "" : ",") + std::to_string(id);
  }
  sim::SimDynamixel device(config);
  return serve_on_pty(
      device, "simulated Dynamixel bus (IDs " + ids + ")",
      [&] {
        std::string line = "positions:";
        for (std::size_t i = 0; i < config.servos.size() && i < 8; ++i)
          line += " " + std::to_string(static_cast<long>(device.position(i)));
        return line;
      },
      out, err);
}

}  // namespace avar::app
