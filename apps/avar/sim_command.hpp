#pragma once
// `avar sim maestro|dynamixel --pty`: a simulated device for other programs (or another avar)
// to drive, on a pseudo-terminal.

#include <iosfwd>
#include <vector>

namespace avar::app {

struct SimMaestroOptions {
  bool pty = false;
  int channels = 24;
  int device_number = 12;
  bool crc = false;
};

struct SimDynamixelOptions {
  bool pty = false;
  std::vector<int> ids{1};
};

/// Each prints the pseudo-terminal's path on `out` (one line, nothing else, so scripts can read
/// it), a status line on `err`, and serves until SIGINT/SIGTERM. Returns the exit code.
int run_sim_maestro(const SimMaestroOptions& options, std::ostream& out, std::ostream& err);
int run_sim_dynamixel(const SimDynamixelOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
