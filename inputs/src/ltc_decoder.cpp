#include "avar/inputs/ltc_decoder.hpp"

#include <ltc.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::inputs {

struct LtcDecoder::Handle {
  LTCDecoder* decoder = nullptr;
  ~Handle() {
    if (decoder) ltc_decoder_free(decoder);
  }
};

LtcDecoder::LtcDecoder(double sample_rate, std::optional<FrameRate> rate)
    : handle_(std::make_unique<Handle>()), sample_rate_(sample_rate), rate_(rate) {
  if (!(sample_rate >= 8000 && sample_rate <= 192000))
    throw std::invalid_argument("LTC: sample rate " + std::to_string(sample_rate) + " Hz is outside 8000 to 192000 Hz");
  // Audio samples per frame (the decoder's starting guess; it adapts) at 25 fps; a queue of 32
  // frames covers far more than one feed.
  handle_->decoder = ltc_decoder_create(static_cast<int>(sample_rate / 25.0), 32);
  if (!handle_->decoder) throw std::runtime_error("LTC: libltc could not create a decoder");
}

LtcDecoder::~LtcDecoder() = default;

void LtcDecoder::write(std::span<const float> samples) noexcept {
  // libltc reads the buffer only (it converts to 8-bit samples on its own stack).
  ltc_decoder_write_float(handle_->decoder, const_cast<float*>(samples.data()), samples.size(), fed_);
  fed_ += static_cast<std::int64_t>(samples.size());
}

bool LtcDecoder::next(TimecodeFix& fix, std::int64_t& end_sample) noexcept {
  LTCFrameExt frame{};
  while (ltc_decoder_read(handle_->decoder, &frame) > 0) {
    SMPTETimecode stime{};
    ltc_frame_to_time(&stime, &frame.ltc, 0);
    FrameRate rate = FrameRate::fps25;
    if (rate_) {
      rate = *rate_;
    } else if (frame.ltc.dfbit) {
      rate = FrameRate::fps29_97df;
    } else {
      const double samples = static_cast<double>(frame.off_end - frame.off_start + 1);
      const double fps = sample_rate_ / samples;
      rate = fps < 24.5 ? FrameRate::fps24 : (fps < 27.5 ? FrameRate::fps25 : FrameRate::fps30);
    }
    const Timecode t{stime.hours, stime.mins, stime.secs, stime.frame, rate};
    if (!valid(t)) {
      ++bad_;
      continue;
    }
    ++frames_;
    // Forward, a frame's code fills the frame: it ends as the next frame begins. Played in
    // reverse, it ends where the labelled frame begins.
    fix = TimecodeFix{t, frame.reverse ? 0.0 : 1.0, frame.reverse != 0};
    // libltc extrapolates a frame's edges from its bit lengths; for a frame cut by the first
    // sample (or by noise that only looks like code) they can fall outside the audio fed.
    end_sample = std::clamp<std::int64_t>(frame.reverse ? frame.off_start : frame.off_end, 0, fed_);
    return true;
  }
  return false;
}

}  // namespace avar::inputs
