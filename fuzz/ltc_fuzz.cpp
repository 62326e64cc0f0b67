// Audio from a sound card or a file carrying SMPTE LTC: the decoder (libltc underneath) must
// report only labels valid for their rate, at finite positions, with end samples that never go
// past the samples fed. Input: a flag byte (bit 0: 16-bit little-endian samples, else 8-bit
// unsigned; bit 1: a fixed 25 fps rate; bits 2-3: sample rate 8000, 44100, 48000 or 96000 Hz),
// then the samples, fed in chunks of up to 1024.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <vector>

#include "avar/inputs/ltc_decoder.hpp"
#include "fuzz_bytes.hpp"
#include "timecode_fix_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  const std::uint8_t flags = in.u8();
  const bool sixteen_bit = (flags & 1U) != 0;
  const std::optional<avar::FrameRate> rate =
      (flags & 2U) != 0 ? std::optional<avar::FrameRate>(avar::FrameRate::fps25) : std::nullopt;
  constexpr double kLtcFuzzRates[] = {8000.0, 44100.0, 48000.0, 96000.0};
  avar::inputs::LtcDecoder decoder(kLtcFuzzRates[(flags >> 2U) & 3U], rate);
  std::vector<float> samples;
  const auto bytes = in.rest();
  const std::size_t width = sixteen_bit ? 2 : 1;
  samples.reserve(bytes.size() / width);
  for (std::size_t i = 0; i + width <= bytes.size(); i += width) {
    if (sixteen_bit) {
      const auto value = static_cast<std::int16_t>(static_cast<std::uint16_t>(bytes[i] | (bytes[i + 1] << 8U)));
      samples.push_back(static_cast<float>(value) / 32768.0F);
    } else {
      samples.push_back((static_cast<float>(bytes[i]) - 128.0F) / 128.0F);
    }
  }
  std::int64_t fed = 0;
  std::uint64_t fixes = 0;
  for (std::size_t at = 0; at < samples.size(); at += 1024) {
    const auto chunk = std::span<const float>(samples).subspan(at, std::min<std::size_t>(1024, samples.size() - at));
    fed += static_cast<std::int64_t>(chunk.size());
    decoder.feed(chunk, [&](const avar::inputs::TimecodeFix& fix, std::int64_t end_sample) {
      avar::fuzz::check_timecode_fix(fix);
      if (end_sample < 0 || end_sample > fed) std::abort();
      if (rate && fix.label.rate != *rate) std::abort();
      ++fixes;
    });
  }
  if (decoder.frames() != fixes) std::abort();
  return 0;
}
