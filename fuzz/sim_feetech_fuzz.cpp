// Bytes a host sends simulated Feetech servos (STS or SCS series packets): the request parser
// must take any bytes.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_feetech.hpp"
#include "byte_device_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimFeetechConfig config;
  config.series = in.flag() ? avar::firmware_iface::feetech::Series::scs : avar::firmware_iface::feetech::Series::sts;
  config.servos.resize(2);
  config.servos[0].id = 1;
  config.servos[1].id = 2;
  config.log_limit = 8;
  avar::sim::SimFeetech device(config);
  avar::fuzz::run_byte_device_session(device, in);
  return 0;
}
