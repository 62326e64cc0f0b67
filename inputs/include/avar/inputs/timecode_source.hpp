#pragma once
// A timecode source (LTC audio, MIDI Time Code, Art-Net timecode) as the chase sees it: the
// newest position received and when it arrived, published by the source's own thread through a
// seqlock, read by the loop without locks; and counters of what arrived.

#include <atomic>
#include <cstdint>
#include <string>

#include "avar/core/atomic_counters.hpp"
#include "avar/core/timecode.hpp"
#include "avar/inputs/timecode_fix.hpp"

namespace avar::inputs {

/// The newest position a source received.
struct TimecodeReading {
  std::uint64_t sequence = 0;   ///< positions received so far; 0: none yet
  double seconds = 0;           ///< the source's position at arrival, s since 00:00:00:00
  std::int64_t arrival_ns = 0;  ///< arrival on the source's clock (CLOCK_MONOTONIC; stepped sources: loop time)
  FrameRate rate = FrameRate::fps25;
  bool reverse = false;
};

/// What a source received.
struct TimecodeCounters {
  std::uint64_t fixes = 0;    ///< positions published
  std::uint64_t partial = 0;  ///< messages taken that were not yet a position (MTC quarter frames)
  std::uint64_t ignored = 0;  ///< well-formed traffic of another kind (another Art-Net packet, a note)
  std::uint64_t bad = 0;      ///< malformed messages, dropped without effect on the show
};

/// The counters, kept by the source's thread, read from any thread (avar/core/atomic_counters.hpp).
using AtomicTimecodeCounters = AtomicCounters<TimecodeCounters>;

/// Latest-value mailbox for one writer thread and any number of readers (a seqlock over
/// atomics). publish() and read() are real-time safe: no allocation, lock or system call;
/// read() retries only while a publish is under way.
class TimecodeMailbox {
 public:
  void publish(const TimecodeFix& fix, std::int64_t arrival_ns) noexcept;
  TimecodeReading read() const noexcept;

 private:
  std::atomic<std::uint64_t> version_{0};  ///< odd while a publish is under way
  std::atomic<double> seconds_{0};
  std::atomic<std::int64_t> arrival_ns_{0};
  std::atomic<std::uint8_t> rate_{0};
  std::atomic<bool> reverse_{false};
};

class TimecodeSource {
 public:
  virtual ~TimecodeSource() = default;
  /// Opens the device or socket and starts receiving. Throws std::runtime_error naming what
  /// could not be opened and why. Not real-time.
  virtual void start() = 0;
  /// Stops receiving; latest() keeps the last position. Idempotent.
  virtual void stop() noexcept = 0;
  /// The newest position. Any thread; real-time safe.
  virtual TimecodeReading latest() const noexcept = 0;
  virtual TimecodeCounters counters() const noexcept = 0;
  /// "Art-Net timecode on udp 127.0.0.1:6454", "LTC from show.wav" ...
  virtual std::string describe() const = 0;
  /// True when the source runs on the loop's stepped clock: advance_to() feeds it, and its
  /// arrival times are loop time in ns. Live sources stamp CLOCK_MONOTONIC.
  virtual bool stepped() const noexcept { return false; }
  /// Stepped sources take in everything up to loop time now_ns here (loop thread, real-time
  /// safe); live sources ignore it.
  virtual void advance_to(std::int64_t /*now_ns*/) noexcept {}
};

}  // namespace avar::inputs
