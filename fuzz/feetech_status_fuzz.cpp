// Bytes from a Feetech SCS/STS bus (status packets, echoes, noise), as the link's bus exchange
// frames them, and decode_packet on the raw bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/firmware_iface/feetech_bus_codec.hpp"
#include "avar/firmware_iface/feetech_codec.hpp"
#include "bus_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  avar::firmware_iface::FeetechBusCodec codec;
  avar::fuzz::run_bus_stream(codec, in);

  namespace ft = avar::firmware_iface::feetech;
  ft::Packet packet;
  std::size_t consumed = 0;
  const ft::DecodeResult r = ft::decode_packet(in, &packet, &consumed);
  if (consumed > size) std::abort();
  if (r == ft::DecodeResult::ok && packet.params.size() >= 2) (void)ft::get_word(ft::Series::scs, packet.params);
  return 0;
}
