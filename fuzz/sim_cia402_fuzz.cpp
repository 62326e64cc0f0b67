// Frames a host sends a simulated CANopen CiA 402 drive (NMT, SYNC, SDO, RPDO): the request
// parser must take any frame.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_cia402_drive.hpp"
#include "can_node_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimCia402DriveConfig config;
  config.node = 1;
  config.heartbeat_ms = 100;
  config.supported_modes = (1u << 7) | (1u << 0) | (1u << 2);
  avar::sim::SimCia402Drive node(config);
  avar::fuzz::run_can_node_session(node, in);
  return 0;
}
