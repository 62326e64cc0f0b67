#pragma once
// `avar sim maestro|dynamixel|feetech|ssc32|dmx|slcan --pty`: a simulated device for other programs (or another avar)
// to drive, on a pseudo-terminal.

#include <iosfwd>
#include <string>
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

struct SimFeetechOptions {
  bool pty = false;
  std::vector<int> ids{1};
  std::string series = "sts";  ///< "sts" or "scs"
  int baud = 1'000'000;
};

struct SimSsc32Options {
  bool pty = false;
};

struct SimDmxOptions {
  bool pty = false;
};

struct SimSlcanOptions {
  bool pty = false;
  std::string drive = "odrive";  ///< a CAN drive protocol: odrive, cia402, mit
  std::vector<int> ids{1};       ///< node ids of the drives on the bus
  int bitrate = 1'000'000;       ///< bit/s of the bus
};

/// Each prints the pseudo-terminal's path on `out` (one line, nothing else, so scripts can read
/// it), a status line on `err`, and serves until SIGINT/SIGTERM. Returns the exit code.
int run_sim_maestro(const SimMaestroOptions& options, std::ostream& out, std::ostream& err);
int run_sim_dynamixel(const SimDynamixelOptions& options, std::ostream& out, std::ostream& err);
int run_sim_feetech(const SimFeetechOptions& options, std::ostream& out, std::ostream& err);
int run_sim_ssc32(const SimSsc32Options& options, std::ostream& out, std::ostream& err);
int run_sim_dmx(const SimDmxOptions& options, std::ostream& out, std::ostream& err);
int run_sim_slcan(const SimSlcanOptions& options, std::ostream& out, std::ostream& err);

}  // namespace avar::app
