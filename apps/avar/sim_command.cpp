#include "avar/sim_command.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "avar/assembly/can_drive.hpp"
#include "avar/rig/can_drive_schema.hpp"
#include "avar/exit_codes.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/feetech_codec.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_dmx.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_feetech.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"
#include "avar/sim/sim_ssc32.hpp"

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

int refuse_without_pty(std::ostream& err) {
  err << "error: say where to serve: --pty (a pseudo-terminal)\n";
  return kExitBadInput;
}

/// Checks bus IDs (each 0..max_id, none twice) into `ids`; reports the first bad one on err.
bool checked_ids(const std::vector<int>& given, int max_id, const char* what, std::vector<std::uint8_t>& ids, std::ostream& err) {
  for (int id : given) {
    if (id < 0 || id > max_id) {
      err << "error: --ids: " << id << " is not " << what << "; expected 0 to " << max_id << "\n";
      return false;
    }
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
      err << "error: --ids: " << id << " is given twice; every servo on a bus needs its own ID\n";
      return false;
    }
    ids.push_back(static_cast<std::uint8_t>(id));
  }
  return true;
}

std::string id_list(const std::vector<std::uint8_t>& ids) {
  std::string out;
  for (std::uint8_t id : ids) out += (out.empty() ? "" : ",") + std::to_string(id);
  return out;
}

}  // namespace

int run_sim_maestro(const SimMaestroOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) return refuse_without_pty(err);
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
  if (!options.pty) return refuse_without_pty(err);
  std::vector<std::uint8_t> ids;
  if (!checked_ids(options.ids, firmware_iface::dynamixel::kMaxId, "a Dynamixel ID", ids, err)) return kExitBadInput;
  sim::SimDynamixelConfig config;
  for (std::uint8_t id : ids) {
    sim::SimDynamixelServo servo;
    servo.id = id;
    config.servos.push_back(servo);
  }
  sim::SimDynamixel device(config);
  return serve_on_pty(
      device, "simulated Dynamixel bus (IDs " + id_list(ids) + ")",
      [&] {
        std::string line = "positions:";
        for (std::size_t i = 0; i < config.servos.size() && i < 8; ++i)
          line += " " + std::to_string(static_cast<long>(device.position(i)));
        return line;
      },
      out, err);
}

int run_sim_feetech(const SimFeetechOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) return refuse_without_pty(err);
  std::vector<std::uint8_t> ids;
  if (!checked_ids(options.ids, firmware_iface::feetech::kMaxId, "a Feetech ID", ids, err)) return kExitBadInput;
  sim::SimFeetechConfig config;
  if (options.series == "sts" || options.series == "scs") {
    config.series = options.series == "sts" ? firmware_iface::feetech::Series::sts : firmware_iface::feetech::Series::scs;
  } else {
    err << "error: --series: '" << options.series << "' is not a Feetech series; expected sts or scs\n";
    return kExitBadInput;
  }
  if (sim::SimFeetech::baud_code(options.baud) < 0) {
    err << "error: --baud: a Feetech servo cannot run at " << options.baud
        << "; expected 1000000, 500000, 250000, 128000, 115200, 76800, 57600, 38400, 19200, 14400, 9600 or 4800\n";
    return kExitBadInput;
  }
  config.baud = options.baud;
  for (std::uint8_t id : ids) {
    sim::SimFeetechServo servo;
    servo.id = id;
    config.servos.push_back(servo);
  }
  sim::SimFeetech device(config);
  return serve_on_pty(
      device,
      "simulated Feetech " + std::string(options.series == "sts" ? "STS" : "SCS") + " bus (IDs " + id_list(ids) + ", " +
          std::to_string(options.baud) + " baud)",
      [&] {
        std::string line = "positions:";
        for (std::size_t i = 0; i < config.servos.size() && i < 8; ++i)
          line += " " + std::to_string(std::lround(device.position(i)));
        return line;
      },
      out, err);
}

int run_sim_ssc32(const SimSsc32Options& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) return refuse_without_pty(err);
  sim::SimSsc32 device(sim::SimSsc32Config{});
  return serve_on_pty(
      device, "simulated SSC-32U (32 channels)",
      [&] {
        std::string line = "outputs (µs):";
        for (int ch = 0; ch < 12; ++ch) line += " " + std::to_string(std::lround(device.output_pulse(ch)));
        return line;
      },
      out, err);
}

int run_sim_dmx(const SimDmxOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) return refuse_without_pty(err);
  sim::SimDmx device(sim::SimDmxConfig{});
  return serve_on_pty(
      device, "simulated DMX USB Pro (one universe)",
      [&] {
        std::string line = std::to_string(device.frames_received()) + " frames; slots:";
        for (int address = 1; address <= 16; ++address) line += " " + std::to_string(device.slot(address));
        return line;
      },
      out, err);
}

int run_sim_slcan(const SimSlcanOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.pty) return refuse_without_pty(err);
  const rig::CanDriveSchema* schema = rig::find_drive_schema(options.drive);
  const assembly::CanDriveProtocol* drive = assembly::find_can_drive(options.drive);
  if (!schema || !drive) {
    err << "error: --drive: '" << options.drive << "' is not a CAN drive protocol; expected one of: " << rig::drive_names()
        << "\n";
    return kExitBadInput;
  }
  if (!firmware_iface::is_standard_can_bitrate(options.bitrate)) {
    err << "error: --bitrate: " << options.bitrate
        << " is not a CAN bitrate; expected 10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000 or 1000000\n";
    return kExitBadInput;
  }
  if (!schema->accepts_bitrate(options.bitrate)) {
    err << "error: --bitrate: a " << schema->device_name << " cannot run at " << options.bitrate
        << "; expected one of: " << schema->bitrates_text << "\n";
    return kExitBadInput;
  }
  assembly::CanBusOptions bus;
  bus.bitrate = options.bitrate;
  std::vector<assembly::SimulatedDrive> drives;
  std::vector<sim::CanNode*> nodes;
  std::string ids;
  for (int id : options.ids) {
    if (id < schema->node_low || id > schema->node_high) {
      err << "error: --ids: " << id << " is not a " << schema->device_name << " node; expected " << schema->node_low << " to "
          << schema->node_high << "\n";
      return kExitBadInput;
    }
    if (std::find(options.ids.begin(), options.ids.end(), id) !=
        options.ids.begin() + static_cast<std::ptrdiff_t>(drives.size())) {
      err << "error: --ids: " << id << " is given twice; every drive on a bus needs its own node id\n";
      return kExitBadInput;
    }
    drives.push_back(drive->make_simulated(nullptr, static_cast<std::uint32_t>(id), 0, bus));
    nodes.push_back(drives.back().node.get());
    ids += (ids.empty() ? "" : ",") + std::to_string(id);
  }
  sim::SimSlcanAdapter device(sim::SimSlcanConfig{.bus_bitrate = options.bitrate}, nodes);
  return serve_on_pty(
      device,
      "simulated SLCAN adapter with " + std::string(schema->device_name) + (drives.size() == 1 ? "" : "s") + " at node" +
          (drives.size() == 1 ? " " : "s ") + ids + " on a " + std::to_string(options.bitrate) + " bit/s bus",
      [&] {
        std::string line = std::string("positions (") + schema->device_unit + "):";
        char value[24];
        for (std::size_t i = 0; i < drives.size() && i < 8; ++i) {
          std::snprintf(value, sizeof value, " %.3f", drives[i].device_position());
          line += value;
        }
        return line;
      },
      out, err);
}

}  // namespace avar::app
