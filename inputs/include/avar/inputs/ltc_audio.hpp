#pragma once
// LTC audio as files: libltc's encoder (to make timecode audio: test signals, a sync track for a
// show) and mono WAV reading and writing through libsndfile. Not real-time (they allocate).

#include <string>
#include <vector>

#include "avar/core/timecode.hpp"

namespace avar::inputs {

/// `frames` frames of LTC from `start` (counting up), mono samples in -1..1 at sample_rate Hz.
std::vector<float> encode_ltc_audio(const Timecode& start, std::size_t frames, double sample_rate);

struct MonoAudio {
  std::vector<float> samples;  ///< the first channel, -1..1
  double sample_rate = 0;      ///< Hz
};

/// Reads a sound file (WAV, FLAC, ...) whole; the first channel is kept. Throws
/// std::runtime_error "FILE: cannot read (why)" or "FILE: has no samples".
MonoAudio read_mono_audio(const std::string& path);

/// Writes mono 16-bit PCM WAV. Throws std::runtime_error when it cannot.
void write_mono_wav(const std::string& path, const std::vector<float>& samples, double sample_rate);

}  // namespace avar::inputs
