// Text lines a host sends a simulated SSC-32 (moves, offsets, outputs, queries): the request
// parser must take any bytes, over-long lines included.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_ssc32.hpp"
#include "byte_device_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimSsc32Config config;
  config.log_limit = 8;
  avar::sim::SimSsc32 device(config);
  avar::fuzz::run_byte_device_session(device, in);
  return 0;
}
