#include "avar/config/audio_file.hpp"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace avar::config {

MonoAudio read_mono_audio(const std::string& path, const SourceLocation& where) {
  SF_INFO info{};
  const std::unique_ptr<SNDFILE, int (*)(SNDFILE*)> file(sf_open(path.c_str(), SFM_READ, &info), sf_close);
  if (!file)
    throw InputError(where, "cannot read audio file '" + path + "' (" + sf_strerror(nullptr) +
                                "); expected a readable sound file (WAV, FLAC or OGG)");
  if (info.frames <= 0 || info.channels <= 0 || info.samplerate <= 0)
    throw InputError(where, "audio file '" + path + "' holds no samples; expected a recording of at least one sample");
  const auto channels = static_cast<std::size_t>(info.channels);
  const auto frames = static_cast<std::size_t>(info.frames);
  std::vector<float> interleaved(frames * channels);
  const sf_count_t read = sf_readf_float(file.get(), interleaved.data(), info.frames);
  if (read <= 0)
    throw InputError(where,
                     "cannot decode audio file '" + path + "' (" + sf_strerror(file.get()) + "); expected a readable sound file");
  MonoAudio audio;
  audio.sample_rate_hz = info.samplerate;
  audio.samples.resize(static_cast<std::size_t>(read));
  for (std::size_t f = 0; f < audio.samples.size(); ++f) {
    float sum = 0;
    for (std::size_t c = 0; c < channels; ++c) sum += interleaved[f * channels + c];
    audio.samples[f] = sum / static_cast<float>(channels);
  }
  return audio;
}

std::vector<float> audio_peaks(const MonoAudio& audio, double bucket_s) {
  const auto per_bucket = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(bucket_s * audio.sample_rate_hz)));
  std::vector<float> peaks;
  peaks.reserve(2 * (audio.samples.size() / per_bucket + 1));
  for (std::size_t from = 0; from < audio.samples.size(); from += per_bucket) {
    const auto first = audio.samples.begin() + static_cast<std::ptrdiff_t>(from);
    const auto [low, high] =
        std::minmax_element(first, first + static_cast<std::ptrdiff_t>(std::min(per_bucket, audio.samples.size() - from)));
    peaks.push_back(*low);
    peaks.push_back(*high);
  }
  return peaks;
}

}  // namespace avar::config
