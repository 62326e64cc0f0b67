// A show track made from audio: `jaw: {audio: {file, open, ...}}` is fitted at load time (path
// relative to the show file), stays closed in silence, starts where the show says, and bad
// fields are refused with file, line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"
#include "../support/wav_file.hpp"
#include "avar/config/show_file.hpp"

namespace avar::config {
namespace {

/// A 2 s mono WAV at 16 kHz: a -9 dBFS 700 Hz tone from 0.6 to 1.2 s, silence elsewhere; its
/// file name (it sits next to the show files of the test).
std::string audio_track_wav() {
  const std::string path = testing::temp_path("voice.wav");
  std::vector<float> x(32000, 0.0f);
  for (std::size_t i = 9600; i < 19200; ++i)
    x[i] = static_cast<float>(0.5 * std::sin(2 * 3.14159265358979 * 700 * static_cast<double>(i) / 16000));
  testing::write_wav_mono16(path, x, 16000);
  return std::filesystem::path(path).filename().string();
}

TEST(ShowAudioTrack, LoadsAFittedJawTrackRelativeToTheShowFile) {
  const std::string wav = audio_track_wav();
  const std::string show_path = testing::write_temp_file(
      "show.yaml", "duration: 4\ntracks:\n  jaw:\n    audio: {file: " + wav + ", open: 25, start: 1, lead_ms: 50}\n");
  const playback::Show show = load_show_file(show_path);
  ASSERT_EQ(show.tracks.size(), 1u);
  const auto& track = show.tracks[0];
  EXPECT_EQ(track.channel, "jaw");
  EXPECT_EQ(track.where.line, 3);
  EXPECT_GT(track.raw.keys.size(), 3u);
  playback::CurveCursor cursor;
  for (double t = 0; t <= 4; t += 0.005) {
    const double v = track.curve.evaluate(t, cursor);
    ASSERT_GE(v, 0.0) << t;
    ASSERT_LE(v, 25.0) << t;
    // The tone sounds from 1.6 to 2.2 s of the show; the jaw may move 50 ms (and a frame) early.
    if (t < 1.53 || t > 2.8) {
      ASSERT_EQ(v, 0.0) << "silence moved the jaw at " << t << " s";
    }
  }
  EXPECT_GT(track.curve.evaluate(1.9, cursor), 24.0);
}

TEST(ShowAudioTrack, AudioLongerThanTheShowIsCut) {
  const std::string wav = audio_track_wav();
  const std::string show_path = testing::write_temp_file(
      "show.yaml", "duration: 0.9\ntracks:\n  jaw: {audio: {file: " + wav + ", open: -10, closed: 5}}\n");
  const playback::Show show = load_show_file(show_path);
  EXPECT_LE(show.tracks[0].raw.keys.back().time, 0.9);
  playback::CurveCursor cursor;
  EXPECT_LT(show.tracks[0].curve.evaluate(0.85, cursor), 0.0) << "the mouth opens downward here";
}

TEST(ShowAudioTrack, BadFieldsNameFileLineAndColumn) {
  const std::string wav = audio_track_wav();
  const auto error = [&](const std::string& audio) {
    return testing::load_error([](const std::string& p) { (void)load_show_file(p); },
                               "duration: 4\ntracks:\n  jaw:\n    audio: " + audio + "\n");
  };
  EXPECT_EQ(error("{file: nowhere.wav, open: 25}").substr(0, 10), ":4:19: can");
  EXPECT_NE(error("{file: nowhere.wav, open: 25}").find("expected a readable sound file (WAV, FLAC or OGG)"), std::string::npos);
  EXPECT_EQ(error("{file: " + wav + "}"),
            ":4:12: missing field 'open' in the audio source of track 'jaw' (open: the channel value of the open mouth)");
  EXPECT_NE(error("{file: " + wav + ", open: 25, gain: 2}").find(":4:"), std::string::npos);
  EXPECT_NE(error("{file: " + wav + ", open: 25, gain: 2}").find("gain"), std::string::npos);
  EXPECT_NE(error("{file: " + wav + ", open: 25, lead_ms: -5}").find("expected lead_ms to be 0 or more"), std::string::npos);
  EXPECT_NE(error("{file: " + wav + ", open: 25, band_hz: [3000, 300]}").find("expected 0 < low < high"), std::string::npos);
  EXPECT_NE(error("{file: " + wav + ", open: 25, start: 9}").find("audio start 9 s is outside the show"), std::string::npos);
  EXPECT_NE(error("{file: " + wav + ", open: 25, gate_db: -10}").find("expected full_db (-12) above gate_db (-10)"),
            std::string::npos);
  const std::string both = testing::load_error(
      [](const std::string& p) { (void)load_show_file(p); },
      "duration: 4\ntracks:\n  jaw:\n    audio: {file: " + wav + ", open: 25}\n    keys: [{time: 0, value: 0}]\n");
  EXPECT_NE(both.find("made from audio"), std::string::npos) << both;
}

}  // namespace
}  // namespace avar::config
