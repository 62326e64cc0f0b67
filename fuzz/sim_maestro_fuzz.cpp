// Bytes a host sends a simulated Maestro (compact, Pololu and Mini SSC commands, with or without
// CRC, with or without baud detection): the request parser must take any bytes.
#include <cstddef>
#include <cstdint>

#include "avar/sim/sim_maestro.hpp"
#include "byte_device_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimMaestroConfig config;
  const std::uint8_t options = in.u8();
  static constexpr int kCounts[4] = {6, 12, 18, 24};
  config.channel_count = kCounts[options & 3];
  config.crc = (options & 4) != 0;
  config.baud_detect = (options & 8) != 0;
  config.mini_ssc_offset = in.u8() == 255 ? 0 : 12;
  config.log_limit = 8;
  avar::sim::SimMaestro device(config);
  avar::fuzz::run_byte_device_session(device, in);
  return 0;
}
