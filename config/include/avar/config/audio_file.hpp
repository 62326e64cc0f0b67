#pragma once
// Reading sound files (libsndfile: WAV, FLAC, OGG/Vorbis and the other formats it knows, any
// sample rate, any channel count) as one mono signal. Load time: allocates, throws InputError.

#include <string>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::config {

struct MonoAudio {
  std::vector<float> samples;  ///< the mean of all channels, full scale +-1
  double sample_rate_hz = 0;
  double duration_s() const { return sample_rate_hz > 0 ? static_cast<double>(samples.size()) / sample_rate_hz : 0; }
};

/// Reads the whole file at `path`, mixing its channels down to mono. Throws InputError at
/// `where` (the option or show key that named the file), naming the path and libsndfile's
/// reason, when the file cannot be opened or decoded, or holds no samples.
MonoAudio read_mono_audio(const std::string& path, const SourceLocation& where);

/// The sound's outline for drawing it: for each `bucket_s` of the sound (the last one shorter),
/// the lowest and the highest sample, full scale +-1, as [low0, high0, low1, high1, ...].
std::vector<float> audio_peaks(const MonoAudio& audio, double bucket_s);

}  // namespace avar::config
