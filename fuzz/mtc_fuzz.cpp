// MIDI Time Code from a MIDI port (RtMidi delivers whole messages): the decoder must report fixes
// only with a label valid for its rate and a quarter-frame offset within -0.25..1.5 frames.
// Input: messages, each a length byte (mod 16) and its bytes; a length byte of 0xFF resets.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/inputs/mtc_decoder.hpp"
#include "fuzz_bytes.hpp"
#include "timecode_fix_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::inputs::MtcDecoder decoder;
  while (!in.empty()) {
    const std::uint8_t length = in.u8();
    if (length == 0xFF) {
      decoder.reset();
      continue;
    }
    const auto message = in.take(length % 16U);
    avar::inputs::TimecodeFix fix;
    if (decoder.decode(message, fix) != avar::inputs::MtcVerdict::fix) continue;
    avar::fuzz::check_timecode_fix(fix);
    if (!(fix.frames_after >= -0.25 && fix.frames_after <= 1.5)) std::abort();
  }
  return 0;
}
