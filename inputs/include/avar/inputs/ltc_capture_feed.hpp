#pragma once
// Capture periods into the shared LTC decode path: an interleaved period of signed 16-bit or
// float samples (as a sound card delivers it) is mixed to mono and fed to an LtcFeed, stamped
// with the arrival of its end. Everything above the device read, so it can be tested
// with synthetic periods.
//
// Construction allocates (the period buffer and mono scratch); take() is real-time safe. One
// writer thread (the capture thread); latest() and counters() of feed() from any thread.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "avar/inputs/ltc_feed.hpp"

namespace avar::inputs {

enum class PcmSampleFormat { s16, f32 };

class LtcCaptureFeed {
 public:
  /// sample_rate Hz; channels 1 to 32 (std::invalid_argument otherwise); period_frames > 0.
  LtcCaptureFeed(double sample_rate, unsigned channels, PcmSampleFormat format, std::size_t period_frames);

  /// Room for period_frames() interleaved frames in format(): where the device reads to.
  void* buffer() noexcept { return buffer_.data(); }
  std::size_t period_frames() const noexcept { return mono_.size(); }
  unsigned channels() const noexcept { return channels_; }
  PcmSampleFormat format() const noexcept { return format_; }

  /// The first `frames` frames in buffer() (at most period_frames()) are the next capture, whose
  /// end arrived at end_ns (as LtcFeed::feed). Mixes them to mono (the channels' mean), decodes.
  void take(std::size_t frames, std::int64_t end_ns) noexcept;

  const LtcFeed& feed() const noexcept { return feed_; }

 private:
  LtcFeed feed_;
  unsigned channels_;
  PcmSampleFormat format_;
  std::vector<float> buffer_;  ///< interleaved samples, s16 or f32 (floats keep the alignment)
  std::vector<float> mono_;
};

}  // namespace avar::inputs
