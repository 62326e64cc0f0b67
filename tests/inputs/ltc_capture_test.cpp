#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "avar/inputs/alsa_ltc_source.hpp"
#include "avar/inputs/ltc_audio.hpp"
#include "avar/inputs/ltc_capture_feed.hpp"

namespace avar::inputs {
namespace {

constexpr double kLtcCapRate = 48000;
constexpr std::int64_t kLtcCapBaseNs = 5'000'000'000;  // the capture clock when sample 0 began

/// Feeds `mono` through `feed` in periods of the sizes in `periods` (cycled), as `channels`
/// interleaved copies of each sample in the feed's format, each period stamped with the ideal
/// arrival of its end. After every period the latest position must be the LTC's own time at its
/// arrival (start label + elapsed audio), as a capture device's stamps would give.
void ltccap_play(LtcCaptureFeed& feed, const std::vector<float>& mono, const std::vector<std::size_t>& periods,
                 const Timecode& start) {
  std::size_t at = 0;
  for (std::size_t k = 0; at < mono.size(); ++k) {
    const std::size_t n = std::min({periods[k % periods.size()], mono.size() - at, feed.period_frames()});
    for (std::size_t f = 0; f < n; ++f) {
      for (unsigned c = 0; c < feed.channels(); ++c) {
        const std::size_t i = f * feed.channels() + c;
        if (feed.format() == PcmSampleFormat::f32) {
          static_cast<float*>(feed.buffer())[i] = mono[at + f];
        } else {
          static_cast<std::int16_t*>(feed.buffer())[i] = static_cast<std::int16_t>(std::lround(mono[at + f] * 32767.0F));
        }
      }
    }
    at += n;
    const auto end_ns = kLtcCapBaseNs + static_cast<std::int64_t>(std::llround(static_cast<double>(at) * 1e9 / kLtcCapRate));
    feed.take(n, end_ns);
    const TimecodeReading r = feed.feed().latest();
    if (r.sequence == 0) continue;
    ASSERT_NEAR(r.seconds - to_seconds(start), static_cast<double>(r.arrival_ns - kLtcCapBaseNs) * 1e-9, 1e-4) << k;
    ASSERT_LE(r.arrival_ns, end_ns);
  }
}

TEST(LtcCaptureFeed, StereoS16PeriodsDecodeWithArrivalStamps) {
  const Timecode start{1, 2, 3, 4, FrameRate::fps25};
  LtcCaptureFeed feed(kLtcCapRate, 2, PcmSampleFormat::s16, 256);
  ltccap_play(feed, encode_ltc_audio(start, 25, kLtcCapRate), {256}, start);
  EXPECT_GE(feed.feed().counters().fixes, 23U);
  EXPECT_EQ(feed.feed().counters().bad, 0U);
  EXPECT_NEAR(feed.feed().latest().seconds, to_seconds(start) + 1.0, 1.0 / 25.0 + 1e-6);
}

TEST(LtcCaptureFeed, ShortMonoFloatReadsDecodeTheSame) {
  // Non-blocking reads return whatever has arrived: periods of any size, some tiny.
  const Timecode start{0, 59, 59, 0, FrameRate::fps30};
  LtcCaptureFeed feed(kLtcCapRate, 1, PcmSampleFormat::f32, 256);
  ltccap_play(feed, encode_ltc_audio(start, 30, kLtcCapRate), {256, 7, 100, 1, 256, 200}, start);
  EXPECT_GE(feed.feed().counters().fixes, 28U);
  EXPECT_EQ(feed.feed().counters().bad, 0U);
}

TEST(LtcCaptureFeed, OneSilentChannelInTheMixStillDecodes) {
  // LTC on the left input only: the mean halves it, well above the decoder's threshold.
  const Timecode start{10, 0, 0, 0, FrameRate::fps24};
  const std::vector<float> ltc = encode_ltc_audio(start, 24, kLtcCapRate);
  LtcCaptureFeed feed(kLtcCapRate, 2, PcmSampleFormat::f32, 480);
  for (std::size_t at = 0; at < ltc.size(); at += 480) {
    const std::size_t n = std::min<std::size_t>(480, ltc.size() - at);
    auto* buffer = static_cast<float*>(feed.buffer());
    for (std::size_t f = 0; f < n; ++f) {
      buffer[2 * f] = ltc[at + f];
      buffer[2 * f + 1] = 0.0F;
    }
    feed.take(n, static_cast<std::int64_t>(at + n));
  }
  EXPECT_GE(feed.feed().counters().fixes, 22U);
  EXPECT_EQ(feed.feed().latest().rate, FrameRate::fps24);
}

TEST(LtcCaptureFeed, RefusesImpossibleLayouts) {
  EXPECT_THROW(LtcCaptureFeed(kLtcCapRate, 0, PcmSampleFormat::s16, 256), std::invalid_argument);
  EXPECT_THROW(LtcCaptureFeed(kLtcCapRate, 33, PcmSampleFormat::s16, 256), std::invalid_argument);
  EXPECT_THROW(LtcCaptureFeed(kLtcCapRate, 1, PcmSampleFormat::s16, 0), std::invalid_argument);
  EXPECT_THROW(LtcCaptureFeed(100.0, 1, PcmSampleFormat::f32, 256), std::invalid_argument);
}

TEST(AlsaLtcSource, ABadDeviceNameIsANamedError) {
  AlsaLtcSource source("no_such_avar_pcm");
  try {
    source.start();
    FAIL() << "opened a device that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ALSA capture device 'no_such_avar_pcm': cannot open ("), std::string::npos) << e.what();
  }
  EXPECT_EQ(source.latest().sequence, 0U);
  EXPECT_EQ(source.describe(), "LTC from ALSA capture device no_such_avar_pcm");
  source.stop();
}

/// Captures a tenth of a second from `device` and stops, or skips when it cannot be opened.
void ltccap_capture_briefly(const std::string& device) {
  AlsaLtcSource source(device);
  try {
    source.start();
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no ALSA capture device: " << e.what();
  }
  // A tenth of a second of audio (silence or anything: no LTC is needed) arrives within 2 s.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  const auto wanted = static_cast<std::uint64_t>(source.sample_rate() / 10);
  while (source.frames_captured() < wanted && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_GE(source.frames_captured(), wanted);
  source.stop();
  EXPECT_EQ(source.describe().find("capture failed"), std::string::npos) << source.describe();
  EXPECT_EQ(source.counters().bad, 0U);
}

TEST(AlsaLtcSource, CapturesFromTheDefaultDevice) { ltccap_capture_briefly("default"); }

TEST(AlsaLtcSource, CapturesFromTheFirstCard) { ltccap_capture_briefly("hw:0"); }

// alsa-lib's null PCM (silence, no hardware): the capture thread's read loop runs here too.
TEST(AlsaLtcSource, CapturesFromTheNullDevice) { ltccap_capture_briefly("null"); }

}  // namespace
}  // namespace avar::inputs
