#include "avar/sim_command.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <ostream>

#include "avar/exit_codes.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_maestro.hpp"

namespace avar::app {

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
  err << "simulated Maestro (" << options.channels << " channels, device number " << options.device_number
      << (options.crc ? ", CRC on" : "") << ") on " << host.slave_path() << "; Ctrl-C to stop\n";

  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  std::uint64_t last_bytes = 0;
  const timespec half_second{0, 500'000'000};
  // The host serves on its own thread; this loop only reports, twice a second, until a signal.
  while (sigtimedwait(&stop_signals, nullptr, &half_second) < 0) {
    const std::uint64_t bytes = host.with_device([&](sim::ByteDevice& d) { return d.bytes_received(); });
    if (terminal && bytes != last_bytes) {
      char line[256];
      int used = std::snprintf(line, sizeof line, "\r%llu bytes received; outputs (µs):", static_cast<unsigned long long>(bytes));
      host.with_device([&](sim::ByteDevice&) {
        for (int ch = 0; ch < options.channels && ch < 12 && used < 200; ++ch)
          used += std::snprintf(line + used, sizeof line - static_cast<std::size_t>(used), " %.0f", device.output_pulse(ch) / 4.0);
      });
      err << line << "\033[K" << std::flush;
    }
    last_bytes = bytes;
  }
  if (terminal) err << '\n';
  const std::uint64_t total = host.with_device([&](sim::ByteDevice& d) { return d.bytes_received(); });
  err << "simulated Maestro stopped after " << total << " bytes\n";
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return kExitOk;
}

}  // namespace avar::app
