#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <thread>
#include <vector>

#include "avar/inputs/artnet_timecode_codec.hpp"
#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"
#include "avar/inputs/ltc_file_source.hpp"
#include "avar/inputs/midi_input.hpp"
#include "avar/inputs/timecode_inputs.hpp"
#include "../support/temp_file.hpp"
#include "../support/udp_sender.hpp"

namespace avar::inputs {
namespace {

/// Polls `done` until it holds or two seconds pass.
template <class F>
bool tcsrc_eventually(F done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

TEST(TimecodeSourcesArtnet, PublishesGoodPacketsAndCountsBadOnes) {
  ArtnetTimecodeInput input("127.0.0.1", 0);
  input.start();
  const int port = input.bound_port();
  ASSERT_NE(port, 0);
  EXPECT_EQ(input.describe(), "Art-Net timecode on udp 127.0.0.1:" + std::to_string(port));
  testing::UdpSender sender;
  std::array<std::uint8_t, artnet::kTimeCodeSize> packet{};
  const Timecode t{0, 1, 2, 3, FrameRate::fps30};
  ASSERT_EQ(artnet::encode_timecode(t, 0, packet), packet.size());
  const std::int64_t before = monotonic_ns();
  ASSERT_TRUE(sender.send(port, packet));
  ASSERT_TRUE(tcsrc_eventually([&] { return input.latest().sequence == 1; }));
  TimecodeReading r = input.latest();
  EXPECT_DOUBLE_EQ(r.seconds, to_seconds(t));
  EXPECT_EQ(r.rate, FrameRate::fps30);
  EXPECT_GE(r.arrival_ns, before);

  // Bad packets of every kind: counted, the position untouched.
  std::vector<std::vector<std::uint8_t>> bad;
  bad.emplace_back();                                          // empty
  bad.emplace_back(std::vector<std::uint8_t>{'n', 'o', 'p'});  // not Art-Net
  auto p = std::vector<std::uint8_t>(packet.begin(), packet.end());
  bad.emplace_back(p.begin(), p.begin() + 15);  // cut short
  bad.push_back(p), bad.back()[11] = 9;         // old version
  bad.push_back(p), bad.back()[18] = 7;         // bad type
  bad.push_back(p), bad.back()[15] = 61;        // seconds out of range
  for (const auto& b : bad) ASSERT_TRUE(sender.send(port, b));
  auto poll = p;
  poll[8] = 0x00, poll[9] = 0x20;  // an ArtPoll: ignored, not bad
  ASSERT_TRUE(sender.send(port, poll));
  ASSERT_TRUE(tcsrc_eventually([&] { return input.counters().bad == bad.size() && input.counters().ignored == 1; }))
      << input.counters().bad;
  r = input.latest();
  EXPECT_EQ(r.sequence, 1U);
  EXPECT_DOUBLE_EQ(r.seconds, to_seconds(t));
  EXPECT_EQ(input.counters().fixes, 1U);
  input.stop();
}

TEST(TimecodeSourcesArtnet, BusyPortIsAClearError) {
  ArtnetTimecodeInput first("127.0.0.1", 0);
  first.start();
  ArtnetTimecodeInput second("127.0.0.1", first.bound_port());
  try {
    second.start();
    FAIL() << "bound twice";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("address in use"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ArtnetTimecodeInput("not-an-address", 1), std::invalid_argument);
}

TEST(TimecodeSourcesLtcFile, SteppedPlaybackFollowsTheLoopClock) {
  const std::string path = testing::temp_path("ltc.wav");
  const Timecode start{10, 0, 0, 0, FrameRate::fps25};
  write_mono_wav(path, encode_ltc_audio(start, 50, 48000), 48000);
  LtcFileSource source(path, true);
  EXPECT_TRUE(source.stepped());
  EXPECT_NEAR(source.duration_s(), 2.0, 0.01);
  source.start();
  source.advance_to(30'000'000);  // 30 ms: not one frame yet
  EXPECT_EQ(source.latest().sequence, 0U);
  for (std::int64_t ns = 0; ns <= 1'000'000'000; ns += 10'000'000) {
    source.advance_to(ns);
    const TimecodeReading r = source.latest();
    if (r.sequence == 0) continue;
    // The position at arrival is the file's time at that sample, plus its start label.
    ASSERT_NEAR(r.seconds - to_seconds(start), static_cast<double>(r.arrival_ns) * 1e-9, 1e-4);
    ASSERT_LE(r.arrival_ns, ns);
  }
  EXPECT_GE(source.counters().fixes, 23U);
  EXPECT_EQ(source.counters().bad, 0U);
}

TEST(TimecodeSourcesLtcFile, RealTimePlaybackStampsTheMonotonicClock) {
  const std::string path = testing::temp_path("ltc.wav");
  write_mono_wav(path, encode_ltc_audio(Timecode{0, 0, 0, 0, FrameRate::fps30}, 9, 48000), 48000);
  LtcFileSource source(path, false);
  const std::int64_t before = monotonic_ns();
  source.start();
  ASSERT_TRUE(tcsrc_eventually([&] { return source.latest().sequence >= 7; }));
  const TimecodeReading r = source.latest();
  // Within 30 ms: the playback thread starts a little after `before`, more so under the sanitizers.
  EXPECT_NEAR(static_cast<double>(r.arrival_ns - before) * 1e-9, r.seconds, 0.03);
  source.stop();
}

TEST(TimecodeSourcesLtcFile, MissingFileIsAClearError) {
  try {
    LtcFileSource source("/nonexistent/ltc.wav", true);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/ltc.wav: cannot read"), std::string::npos) << e.what();
  }
}

TEST(TimecodeSourcesMtc, OpensAPortOrSaysWhyNot) {
  if (const std::string missing = midi_input_missing(); !missing.empty()) GTEST_SKIP() << "MTC input: " << missing;
  MtcInput input("no such port name at all");
  EXPECT_THROW(input.start(), std::runtime_error);
}

}  // namespace
}  // namespace avar::inputs
