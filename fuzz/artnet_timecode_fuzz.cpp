// An ArtTimeCode datagram from the network: decode_timecode must accept only a label valid for
// its rate, and never read past the datagram.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "avar/inputs/artnet_timecode_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace artnet = avar::inputs::artnet;
  avar::Timecode label;
  std::uint8_t stream_id = 0;
  const auto verdict = artnet::decode_timecode(std::span<const std::uint8_t>(data, size), label, &stream_id);
  if (artnet::to_string(verdict) == nullptr) std::abort();
  if (verdict != artnet::TimeCodeVerdict::ok) return 0;
  if (!avar::valid(label) || size < artnet::kTimeCodeSize || stream_id != data[13]) std::abort();
  // What was read writes back to the same 19 bytes' fields (the Type byte is the rate's code).
  std::uint8_t again[artnet::kTimeCodeSize] = {};
  if (artnet::encode_timecode(label, stream_id, again) != artnet::kTimeCodeSize) std::abort();
  for (std::size_t i = 14; i < artnet::kTimeCodeSize; ++i) {
    if (again[i] != data[i]) std::abort();
  }
  return 0;
}
