#pragma once
// LTC from an ALSA capture device (`default`, `hw:1,0`, `plughw:1` ...): start() opens the PCM
// for capture (float or signed 16-bit, 48000 Hz or the nearest the device takes, mono or mixed to
// mono) and a thread of its own reads periods of 256 frames, stamps each with CLOCK_MONOTONIC
// when its end arrived (less the frames already captured behind it) and decodes it through the
// shared LtcCaptureFeed / LtcFeed path. Overruns (-EPIPE) re-prepare the device and are counted;
// a suspended device (-ESTRPIPE) is resumed. stop() ends the thread within 100 ms and closes.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "avar/inputs/ltc_capture_feed.hpp"
#include "avar/inputs/timecode_source.hpp"

namespace avar::inputs {

class AlsaLtcSource final : public TimecodeSource {
 public:
  explicit AlsaLtcSource(std::string device);
  ~AlsaLtcSource() override;
  AlsaLtcSource(const AlsaLtcSource&) = delete;
  AlsaLtcSource& operator=(const AlsaLtcSource&) = delete;

  /// Opens and configures the device, then captures. Throws std::runtime_error
  /// "ALSA capture device 'DEV': cannot open (ALSA's message)" (or the step that failed).
  void start() override;
  void stop() noexcept override;
  TimecodeReading latest() const noexcept override;
  TimecodeCounters counters() const noexcept override;
  std::string describe() const override;

  /// Capture overruns so far (samples lost; the decoder resynchronises on the next frames).
  std::uint64_t overruns() const noexcept { return overruns_.load(std::memory_order_relaxed); }
  /// Frames captured and decoded so far.
  std::uint64_t frames_captured() const noexcept { return frames_captured_.load(std::memory_order_relaxed); }
  /// Sample rate the device runs at (0 before start()).
  double sample_rate() const noexcept { return feed_ ? feed_->feed().sample_rate() : 0.0; }

 private:
  struct Pcm;
  void capture() noexcept;

  std::string device_;
  std::unique_ptr<Pcm> pcm_;
  std::unique_ptr<LtcCaptureFeed> feed_;
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> frames_captured_{0};
  std::atomic<int> failure_{0};  ///< the ALSA error that ended capture, 0 while none
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace avar::inputs
