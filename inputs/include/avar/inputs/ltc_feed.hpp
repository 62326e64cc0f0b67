#pragma once
// The one LTC decode path every LTC source shares: blocks of mono samples in, positions out to a
// TimecodeMailbox, each stamped with the arrival time of its frame's last sample. A block's
// stamp is when its end arrived (the instant after its last sample: a capture period's return,
// or a file block's due time); a frame that ended earlier in the block is dated back from there
// at the sample rate.
//
// Construction allocates; feed() is real-time safe (no allocation, lock or system call). One
// writer thread; latest() and counters() from any thread.

#include <cstdint>
#include <span>

#include "avar/inputs/ltc_decoder.hpp"
#include "avar/inputs/timecode_source.hpp"

namespace avar::inputs {

class LtcFeed {
 public:
  /// sample_rate: Hz (as LtcDecoder: std::invalid_argument outside 8000 to 192000).
  explicit LtcFeed(double sample_rate) : decoder_(sample_rate) {}

  /// Decodes `samples` (-1..1), the block after the ones fed before, whose end arrived at
  /// block_end_ns (the source's clock). Publishes every frame completed; counts fixes and bad
  /// frames.
  void feed(std::span<const float> samples, std::int64_t block_end_ns) noexcept;

  TimecodeReading latest() const noexcept { return mailbox_.read(); }
  TimecodeCounters counters() const noexcept { return counters_.snapshot(); }
  double sample_rate() const noexcept { return decoder_.sample_rate(); }
  /// Samples fed so far.
  std::int64_t fed() const noexcept { return fed_; }

 private:
  LtcDecoder decoder_;
  std::int64_t fed_ = 0;
  TimecodeMailbox mailbox_;
  AtomicTimecodeCounters counters_;
};

}  // namespace avar::inputs
