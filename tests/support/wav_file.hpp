#pragma once
// Sound files for tests: a mono 16-bit PCM WAV writer (the canonical 44-byte RIFF header), and a
// spoken sentence from espeak-ng padded with silence.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "avar/config/audio_file.hpp"

namespace avar::testing {

/// Writes `samples` (full scale +-1, clipped) as a mono 16-bit PCM WAV file at `rate_hz`.
inline void write_wav_mono16(const std::string& path, std::span<const float> samples, int rate_hz) {
  std::ofstream file(path, std::ios::binary);
  const auto put32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) file.put(static_cast<char>((v >> (8 * i)) & 0xff));
  };
  const auto put16 = [&](std::uint16_t v) {
    for (int i = 0; i < 2; ++i) file.put(static_cast<char>((v >> (8 * i)) & 0xff));
  };
  const auto data_bytes = static_cast<std::uint32_t>(samples.size() * 2);
  file.write("RIFF", 4);
  put32(36 + data_bytes);
  file.write("WAVEfmt ", 8);
  put32(16);
  put16(1);  // PCM
  put16(1);  // mono
  put32(static_cast<std::uint32_t>(rate_hz));
  put32(static_cast<std::uint32_t>(rate_hz) * 2);
  put16(2);
  put16(16);
  file.write("data", 4);
  put32(data_bytes);
  for (const float s : samples) {
    const long v = std::lround(std::clamp(static_cast<double>(s), -1.0, 1.0) * 32767);
    put16(static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  }
}

/// Speaks `text` with espeak-ng into `path`, padded with `pad_s` seconds of silence before and
/// after (in code). Returns "" on success, else what is missing (for GTEST_SKIP).
inline std::string spoken_sentence_wav(const std::string& path, const std::string& text, double pad_s) {
  if (std::system("command -v espeak-ng > /dev/null 2>&1") != 0) return "espeak-ng is not installed (Debian package espeak-ng)";
  const std::string raw = path + ".raw.wav";
  if (std::system(("espeak-ng -w '" + raw + "' '" + text + "'").c_str()) != 0) return "espeak-ng failed to write " + raw;
  const config::MonoAudio spoken = config::read_mono_audio(raw, {raw, 0, 0});
  const auto pad = static_cast<std::size_t>(pad_s * spoken.sample_rate_hz);
  std::vector<float> padded(pad, 0.0f);
  padded.insert(padded.end(), spoken.samples.begin(), spoken.samples.end());
  padded.resize(padded.size() + pad, 0.0f);
  write_wav_mono16(path, padded, static_cast<int>(spoken.sample_rate_hz));
  std::remove(raw.c_str());
  return "";
}

}  // namespace avar::testing
