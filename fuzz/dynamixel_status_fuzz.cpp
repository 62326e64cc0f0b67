// Bytes from a DYNAMIXEL Protocol 2.0 bus (status packets, echoes, noise), as the link's bus
// exchange frames them, and decode_status on the raw bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "avar/firmware_iface/dynamixel_bus_codec.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "bus_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  avar::firmware_iface::DynamixelBusCodec codec;
  avar::fuzz::run_bus_stream(codec, in);

  namespace dxl = avar::firmware_iface::dynamixel;
  std::vector<std::uint8_t> scratch(size);
  dxl::Status status;
  std::size_t consumed = 0;
  const dxl::DecodeResult r = dxl::decode_status(in, scratch, &status, &consumed);
  if (consumed > size) std::abort();
  if (r == dxl::DecodeResult::ok)
    for (std::uint8_t b : status.params) consumed += b;
  return 0;
}
