#pragma once
// LTC decoded from a sound file, as if it played from an audio input: in real time on a thread
// of its own (blocks of 256 samples, each taken when its last sample is due on CLOCK_MONOTONIC),
// or on the loop's stepped clock (--fast: advance_to() decodes up to the loop time). A fix is
// stamped with the time its frame's last sample plays, as an audio device's timestamps would.
// When the file ends no more fixes come: a chase freewheels, then stops.

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "avar/inputs/ltc_audio.hpp"
#include "avar/inputs/ltc_feed.hpp"
#include "avar/inputs/timecode_source.hpp"

namespace avar::inputs {

class LtcFileSource final : public TimecodeSource {
 public:
  /// Reads the file whole (std::runtime_error when it cannot). `stepped`: play on the loop's
  /// clock through advance_to(); otherwise in real time from start().
  LtcFileSource(std::string path, bool stepped);
  ~LtcFileSource() override;
  LtcFileSource(const LtcFileSource&) = delete;
  LtcFileSource& operator=(const LtcFileSource&) = delete;

  void start() override;
  void stop() noexcept override;
  TimecodeReading latest() const noexcept override { return feed_.latest(); }
  TimecodeCounters counters() const noexcept override { return feed_.counters(); }
  std::string describe() const override;
  bool stepped() const noexcept override { return stepped_; }
  /// Stepped only: decodes the samples up to loop time now_ns (time 0: the file's first sample).
  void advance_to(std::int64_t now_ns) noexcept override;
  double duration_s() const noexcept { return static_cast<double>(audio_.samples.size()) / audio_.sample_rate; }

 private:
  /// Decodes the samples not yet fed up to `end`, with arrivals counted from start_ns.
  void decode_until(std::size_t end, std::int64_t start_ns) noexcept;
  void play() noexcept;

  std::string path_;
  bool stepped_;
  MonoAudio audio_;
  LtcFeed feed_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace avar::inputs
