// Messages a host sends a simulated ENTTEC DMX USB Pro (Send DMX, widget parameters, serial
// number): the request parser must take any bytes.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_dmx.hpp"
#include "byte_device_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimDmxConfig config;
  config.fixtures.resize(2);
  config.fixtures[0].address = 1;
  config.fixtures[1].address = 511;
  config.fixtures[1].fine = true;
  avar::sim::SimDmx device(config);
  avar::fuzz::run_byte_device_session(device, in);
  return 0;
}
