#include "avar/inputs/ltc_audio.hpp"

#include <ltc.h>
#include <sndfile.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

namespace avar::inputs {

std::vector<float> encode_ltc_audio(const Timecode& start, std::size_t frames, double sample_rate) {
  const double fps = frames_per_second(start.rate);
  const auto standard = start.rate == FrameRate::fps25 ? LTC_TV_625_50 : LTC_TV_525_60;
  const auto free_encoder = [](LTCEncoder* e) { ltc_encoder_free(e); };
  const std::unique_ptr<LTCEncoder, decltype(free_encoder)> e(ltc_encoder_create(sample_rate, fps, standard, 0), free_encoder);
  if (!e) throw std::runtime_error("LTC: libltc could not create an encoder");
  SMPTETimecode t{};
  std::snprintf(t.timezone, sizeof t.timezone, "+0000");
  t.hours = static_cast<unsigned char>(start.hours);
  t.mins = static_cast<unsigned char>(start.minutes);
  t.secs = static_cast<unsigned char>(start.seconds);
  t.frame = static_cast<unsigned char>(start.frames);
  ltc_encoder_set_timecode(e.get(), &t);
  std::vector<float> audio;
  audio.reserve(static_cast<std::size_t>(static_cast<double>(frames) * sample_rate / fps) + 64);
  for (std::size_t i = 0; i < frames; ++i) {
    ltc_encoder_encode_frame(e.get());
    ltcsnd_sample_t* buffer = nullptr;
    const int n = ltc_encoder_get_bufferptr(e.get(), &buffer, 1);
    for (int k = 0; k < n; ++k) audio.push_back((static_cast<float>(buffer[k]) - 128.0F) / 128.0F);
    ltc_encoder_inc_timecode(e.get());
  }
  return audio;
}

MonoAudio read_mono_audio(const std::string& path) {
  SF_INFO info{};
  SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
  if (!file) throw std::runtime_error(path + ": cannot read (" + sf_strerror(nullptr) + ")");
  const auto close = [](SNDFILE* f) { sf_close(f); };
  const std::unique_ptr<SNDFILE, decltype(close)> owned(file, close);
  if (info.frames <= 0 || info.channels <= 0) throw std::runtime_error(path + ": has no samples");
  std::vector<float> interleaved(static_cast<std::size_t>(info.frames) * static_cast<std::size_t>(info.channels));
  const sf_count_t got = sf_readf_float(file, interleaved.data(), info.frames);
  MonoAudio audio;
  audio.sample_rate = info.samplerate;
  audio.samples.reserve(static_cast<std::size_t>(got));
  for (sf_count_t i = 0; i < got; ++i) audio.samples.push_back(interleaved[static_cast<std::size_t>(i * info.channels)]);
  if (audio.samples.empty()) throw std::runtime_error(path + ": has no samples");
  return audio;
}

void write_mono_wav(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(sample_rate);
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  const sf_count_t n = static_cast<sf_count_t>(samples.size());
  const sf_count_t written = sf_writef_float(file, samples.data(), n);
  sf_close(file);
  if (written != n) throw std::runtime_error(path + ": cannot write all samples");
}

}  // namespace avar::inputs
