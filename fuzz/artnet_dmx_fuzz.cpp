// An ArtDmx datagram from the network: decode_dmx must accept only an even slot count of 2..512
// lying inside the datagram and a 15-bit Port-Address; an accepted packet encodes back to the
// same header fields and slots.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

#include "avar/firmware_iface/artnet_dmx_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace artnet = avar::firmware_iface::artnet;
  const auto packet = artnet::decode_dmx(std::span<const std::uint8_t>(data, size));
  if (!packet) return 0;
  const auto& slots = packet->slots;
  if (slots.size() < 2 || slots.size() > 512 || slots.size() % 2 != 0 || packet->port_address > 32767) std::abort();
  if (slots.data() < data || slots.data() + slots.size() > data + size) std::abort();
  std::uint8_t again[artnet::kDmxHeaderSize + 512] = {};
  const std::size_t written = artnet::encode_dmx(again, packet->sequence, packet->physical, packet->port_address, slots);
  if (written != artnet::dmx_packet_size(slots.size()) || written > size) std::abort();
  if (std::memcmp(again + artnet::kDmxHeaderSize, slots.data(), slots.size()) != 0) std::abort();
  return 0;
}
