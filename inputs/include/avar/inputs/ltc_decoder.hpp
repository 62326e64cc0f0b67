#pragma once
// SMPTE linear timecode (LTC) from audio samples, decoded by libltc. Each decoded frame is a fix
// stamped with the sample at which its code ended (the next frame begins there). The rate comes
// from the frame's length in samples (24, 25 or 30; 29.97 when the drop-frame bit is set) unless
// one is given.
//
// Construction allocates (libltc's decoder); feed() is real-time safe (libltc decodes in place,
// no allocation). One thread per decoder.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "avar/inputs/timecode_fix.hpp"

namespace avar::inputs {

class LtcDecoder {
 public:
  /// sample_rate: of the audio, Hz (8000 to 192000: std::invalid_argument otherwise).
  explicit LtcDecoder(double sample_rate, std::optional<FrameRate> rate = std::nullopt);
  ~LtcDecoder();
  LtcDecoder(const LtcDecoder&) = delete;
  LtcDecoder& operator=(const LtcDecoder&) = delete;

  /// Decodes mono samples (-1..1) that follow the ones fed before; on_fix(const TimecodeFix&,
  /// std::int64_t end_sample) is called for each frame completed, end_sample counting from the
  /// first sample ever fed. Frames whose labels are out of range count as bad and are dropped.
  template <class OnFix>
  void feed(std::span<const float> samples, OnFix&& on_fix) noexcept {
    write(samples);
    TimecodeFix fix;
    std::int64_t end = 0;
    while (next(fix, end)) on_fix(fix, end);
  }

  std::uint64_t frames() const noexcept { return frames_; }
  std::uint64_t bad_frames() const noexcept { return bad_; }
  double sample_rate() const noexcept { return sample_rate_; }

 private:
  void write(std::span<const float> samples) noexcept;
  bool next(TimecodeFix& fix, std::int64_t& end_sample) noexcept;

  struct Handle;
  std::unique_ptr<Handle> handle_;
  double sample_rate_;
  std::optional<FrameRate> rate_;
  std::int64_t fed_ = 0;
  std::uint64_t frames_ = 0;
  std::uint64_t bad_ = 0;
};

}  // namespace avar::inputs
