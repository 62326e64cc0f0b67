// Frames a host sends a simulated ODrive axis (CANSimple commands and requests): the request
// parser must take any frame.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_odrive_axis.hpp"
#include "can_node_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimOdriveAxisConfig config;
  config.node = 3;
  config.encoder_period_s = 0.01;
  if (in.flag()) config.heartbeat_layout = avar::firmware_iface::odrive::HeartbeatLayout::v0_6;
  avar::sim::SimOdriveAxis node(config);
  avar::fuzz::run_can_node_session(node, in);
  return 0;
}
