// Frames a host sends a simulated MIT-protocol motor (enter/exit motor mode, zero, commands):
// the request parser must take any frame.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_mit_motor.hpp"
#include "can_node_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimMitMotorConfig config;
  config.id = 1;
  config.reply_length = in.flag() ? 8 : 6;
  avar::sim::SimMitMotor node(config);
  avar::fuzz::run_can_node_session(node, in);
  return 0;
}
