#include "avar/inputs/ltc_capture_feed.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace avar::inputs {

LtcCaptureFeed::LtcCaptureFeed(double sample_rate, unsigned channels, PcmSampleFormat format, std::size_t period_frames)
    : feed_(sample_rate), channels_(channels), format_(format) {
  if (channels < 1 || channels > 32)
    throw std::invalid_argument("LTC capture: " + std::to_string(channels) + " channels (expected 1 to 32)");
  if (period_frames == 0) throw std::invalid_argument("LTC capture: a period needs at least one frame");
  // float and int16 both fit in a float's room; s16 uses half of it.
  buffer_.resize(period_frames * channels);
  mono_.resize(period_frames);
}

void LtcCaptureFeed::take(std::size_t frames, std::int64_t end_ns) noexcept {
  frames = std::min(frames, mono_.size());
  if (frames == 0) return;
  const float scale = 1.0F / static_cast<float>(channels_);
  if (format_ == PcmSampleFormat::f32) {
    for (std::size_t f = 0; f < frames; ++f) {
      float sum = 0;
      for (unsigned c = 0; c < channels_; ++c) sum += buffer_[f * channels_ + c];
      mono_[f] = sum * scale;
    }
  } else {
    const auto* s16 = reinterpret_cast<const std::int16_t*>(buffer_.data());
    const float s16_scale = scale / 32768.0F;
    for (std::size_t f = 0; f < frames; ++f) {
      float sum = 0;
      for (unsigned c = 0; c < channels_; ++c) sum += static_cast<float>(s16[f * channels_ + c]);
      mono_[f] = sum * s16_scale;
    }
  }
  feed_.feed(std::span<const float>(mono_.data(), frames), end_ns);
}

}  // namespace avar::inputs
