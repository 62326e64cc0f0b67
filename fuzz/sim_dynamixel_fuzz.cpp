// Bytes a host sends simulated DYNAMIXEL servos (Protocol 2.0 instruction packets): the request
// parser must take any bytes.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_dynamixel.hpp"
#include "byte_device_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimDynamixelConfig config;
  config.servos.resize(2);
  config.servos[0].id = 1;
  config.servos[1].id = 2;
  config.log_limit = 8;
  avar::sim::SimDynamixel device(config);
  avar::fuzz::run_byte_device_session(device, in);
  return 0;
}
