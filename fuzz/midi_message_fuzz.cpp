// MIDI messages from a controller (as RtMidi delivers them, one whole message each): the decoder
// must name a control only with a value in its range. Input: a flag byte (14-bit controllers),
// then messages, each a length byte (mod 8) and its bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/inputs/midi_decoder.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::inputs::MidiDecoderConfig config;
  config.fourteen_bit_cc = in.flag();
  avar::inputs::MidiDecoder decoder(config);
  while (!in.empty()) {
    const auto message = in.take(in.u8() % 8);
    avar::inputs::MidiControl control;
    if (!decoder.decode(message, &control)) continue;
    const double low = control.bipolar ? -1.0 : 0.0;
    if (!(control.value >= low && control.value <= 1.0) || control.name().empty()) std::abort();
  }
  return 0;
}
