// Text a host sends a simulated SLCAN adapter (open/close, bitrate, frames, queries), with a
// CiA 402 drive, an ODrive axis and an MIT motor on the bus behind it: the adapter's command
// parser and, through the frames it puts on the bus, each node's request parser must take any
// bytes. Simulated time stops at 2 s (twenty heartbeat periods; every node's timer fires): the
// bus integrates three motors at 4 kHz, and the 30 s of the single-device sessions held this
// target under 200 inputs a second. Each node's own target (sim_cia402, sim_odrive, sim_mit)
// runs 30 s.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "avar/sim/sim_cia402_drive.hpp"
#include "avar/sim/sim_mit_motor.hpp"
#include "avar/sim/sim_odrive_axis.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"
#include "byte_device_session.hpp"

namespace {
constexpr double kMaxSlcanSessionSeconds = 2;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimCia402DriveConfig drive_config;
  drive_config.node = 1;
  avar::sim::SimCia402Drive drive(drive_config);
  avar::sim::SimOdriveAxisConfig axis_config;
  axis_config.node = 3;
  avar::sim::SimOdriveAxis axis(axis_config);
  avar::sim::SimMitMotorConfig motor_config;
  motor_config.id = 5;
  avar::sim::SimMitMotor motor(motor_config);
  avar::sim::SimSlcanConfig config;
  const std::uint8_t options = in.u8();
  config.transmit_acks = (options & 1) != 0;
  config.linux_error_lines = (options & 2) != 0;
  avar::sim::SimSlcanAdapter adapter(config, std::vector<avar::sim::CanNode*>{&drive, &axis, &motor});
  avar::fuzz::run_byte_device_session(adapter, in, kMaxSlcanSessionSeconds);
  return 0;
}
