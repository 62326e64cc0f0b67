// `avar jaw`: a spoken sentence (espeak-ng) padded with silence opens the jaw in speech, keeps it
// exactly closed in silence, and leads the envelope by the configured time; bad input exits 2
// naming the file or option.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/temp_file.hpp"
#include "../support/wav_file.hpp"
#include "avar/config/audio_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"
#include "avar/playback/offline/jaw_from_audio.hpp"

namespace avar::app {
namespace {

using testing::run_avar;

constexpr const char* kJawRig = AVAR_SOURCE_DIR "/examples/rigs/talking-skull.yaml";

/// First time (sampled every millisecond) the curve leaves `closed`, or -1.
double jaw_cmd_first_opening(const playback::Curve& curve, double closed, double until) {
  playback::CurveCursor cursor;
  for (double t = 0; t < until; t += 0.001)
    if (curve.evaluate(t, cursor) != closed) return t;
  return -1;
}

TEST(JawCommand, SpokenSentenceOpensInSpeechStaysClosedInSilenceAndLeads) {
  const std::string wav = testing::temp_path("voice.wav");
  const std::string missing = testing::spoken_sentence_wav(wav, "Good evening, and welcome to the haunted mansion.", 1.0);
  if (!missing.empty()) GTEST_SKIP() << missing;
  const std::string show_path = testing::temp_path("jaw.yaml");
  const auto result = run_avar({"jaw", wav, "--rig", kJawRig, "--channel", "jaw", "--out", show_path, "--lead", "80"});
  ASSERT_EQ(result.code, kExitOk) << result.err;
  EXPECT_NE(result.out.find("lead 80 ms"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("ok: show"), std::string::npos) << result.out;
  const playback::Show show = config::load_show_file(show_path);
  ASSERT_EQ(show.tracks.size(), 1u);
  const playback::Curve& jaw = show.tracks[0].curve;

  // Where the voice is: the envelope (no lead) over the gate, from the same audio.
  const config::MonoAudio audio = config::read_mono_audio(wav, {wav, 0, 0});
  const playback::JawOptions defaults;
  const std::vector<double> envelope = playback::speech_envelope_db(audio.samples, audio.sample_rate_hz, defaults);
  double speech_start = -1, speech_end = -1;
  for (std::size_t k = 0; k < envelope.size(); ++k)
    if (envelope[k] >= defaults.gate_db) {
      if (speech_start < 0) speech_start = static_cast<double>(k) / defaults.frame_rate_hz;
      speech_end = static_cast<double>(k) / defaults.frame_rate_hz;
    }
  ASSERT_GT(speech_start, 0.95) << "the padding is silent";
  ASSERT_LT(speech_end, audio.duration_s() - 0.95);

  // Silence keeps the jaw exactly closed; speech opens it past half its travel.
  playback::CurveCursor cursor;
  double widest = 0;
  for (double t = 0; t <= show.duration; t += 0.002) {
    const double v = jaw.evaluate(t, cursor);
    ASSERT_GE(v, 0.0) << t;
    ASSERT_LE(v, 25.0) << t;
    if (t < speech_start - 0.1 || t > speech_end + 0.6) {
      ASSERT_EQ(v, 0.0) << "silence moved the jaw at " << t << " s";
    }
    widest = std::max(widest, v);
  }
  EXPECT_GT(widest, 12.5);
  // The jaw leaves closed the configured lead before the envelope crosses the gate (one frame of
  // quantisation either side).
  const double opening = jaw_cmd_first_opening(jaw, 0.0, show.duration);
  EXPECT_NEAR(speech_start - opening, 0.080, 0.021) << "jaw opens at " << opening << " s, voice at " << speech_start << " s";
}

TEST(JawCommand, DefaultLeadComesFromTheChannelLimits) {
  const std::string wav = testing::temp_path("burst.wav");
  std::vector<float> burst(16000, 0.0f);
  for (std::size_t i = 6000; i < 10000; ++i) burst[i] = static_cast<float>(0.4 * std::sin(0.3 * static_cast<double>(i)));
  testing::write_wav_mono16(wav, burst, 16000);
  const std::string show_path = testing::temp_path("jaw.yaml");
  const auto result = run_avar({"jaw", wav, "--rig", kJawRig, "--out", show_path});
  ASSERT_EQ(result.code, kExitOk) << result.err;
  // 25 deg at 250 deg/s and 6000 deg/s^2: 0.1 + 0.04167 s rest to rest, half of it.
  EXPECT_NE(result.out.find("lead 70.8333 ms (time to half open"), std::string::npos) << result.out;
}

/// Lines of `text` that start with `prefix`.
std::size_t jaw_cmd_lines(const std::string& text, const std::string& prefix) {
  std::size_t n = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    n += text.compare(at, prefix.size(), prefix) == 0 ? 1 : 0;
    at = end + 1;
  }
  return n;
}

TEST(JawCommand, FeasibilityIsSummarisedAndVerboseListsEverySegment) {
  // Syllables: bursts of tone with short gaps, a jaw that asks a lot of the skull's servo.
  const std::string wav = testing::temp_path("syllables.wav");
  std::vector<float> voice(32000, 0.0f);
  for (std::size_t i = 4000; i < 28000; ++i)
    if ((i / 1600) % 2 == 0) voice[i] = static_cast<float>(0.4 * std::sin(0.3 * static_cast<double>(i)));
  testing::write_wav_mono16(wav, voice, 16000);
  const std::string show_path = testing::temp_path("jaw.yaml");
  const auto brief = run_avar({"jaw", wav, "--rig", kJawRig, "--out", show_path});
  ASSERT_EQ(brief.code, kExitOk) << brief.err;
  const auto summary_at = brief.out.find("feasibility: ");
  ASSERT_NE(summary_at, std::string::npos) << brief.out;
  std::size_t segments = 0, over = 0, near = 0;
  ASSERT_EQ(std::sscanf(brief.out.c_str() + summary_at, "feasibility: %zu segment(s), %zu over a limit, %zu within 10 %% of one",
                        &segments, &over, &near),
            3)
      << brief.out;
  const playback::Show show = config::load_show_file(show_path);
  EXPECT_EQ(segments, show.tracks[0].raw.keys.size() - 1);
  EXPECT_NE(brief.out.find("(--verbose lists every segment)"), std::string::npos) << brief.out;
  // Only the segments over or near a limit, each once; the closing count agrees.
  EXPECT_EQ(jaw_cmd_lines(brief.out, "over: "), over);
  EXPECT_EQ(jaw_cmd_lines(brief.out, "near: "), near);
  EXPECT_EQ(jaw_cmd_lines(brief.out, "segment: "), 0u);
  EXPECT_EQ(jaw_cmd_lines(brief.out, "infeasible: "), 0u);
  EXPECT_NE(brief.out.find("\n" + std::to_string(over) + " segment(s) ask more"), std::string::npos) << brief.out;
  EXPECT_LT(over + near, segments);
  // --verbose: every segment, in the same words.
  const auto full = run_avar({"jaw", wav, "--rig", kJawRig, "--out", show_path, "--verbose"});
  ASSERT_EQ(full.code, kExitOk) << full.err;
  EXPECT_EQ(jaw_cmd_lines(full.out, "over: "), over);
  EXPECT_EQ(jaw_cmd_lines(full.out, "near: "), near);
  EXPECT_EQ(jaw_cmd_lines(full.out, "segment: ") + over + near, segments);
}

TEST(JawCommand, BadInputExitsTwoNamingTheFileOrOption) {
  const std::string show_path = testing::temp_path("jaw.yaml");
  const std::string nowhere = testing::temp_path("missing.wav");
  auto r = run_avar({"jaw", nowhere, "--rig", kJawRig, "--out", show_path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(nowhere), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a readable sound file"), std::string::npos) << r.err;

  const std::string not_audio = testing::temp_path("text.wav");
  { std::ofstream(not_audio) << "this is not a sound\n"; }
  r = run_avar({"jaw", not_audio, "--rig", kJawRig, "--out", show_path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(not_audio), std::string::npos) << r.err;

  const std::string wav = testing::temp_path("quiet.wav");
  const std::vector<float> quiet(800, 0.0f);
  testing::write_wav_mono16(wav, quiet, 8000);
  r = run_avar({"jaw", wav, "--rig", kJawRig, "--channel", "nose", "--out", show_path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--channel: rig 'talking-skull' has no channel 'nose'"), std::string::npos) << r.err;
  r = run_avar({"jaw", wav, "--rig", kJawRig, "--band", "3000-300", "--out", show_path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--band: found '3000-300'; expected LO-HI"), std::string::npos) << r.err;
  r = run_avar({"jaw", wav, "--rig", kJawRig, "--open", "40", "--out", show_path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--open: found 40 deg; expected within channel 'jaw' limits [0, 25]"), std::string::npos) << r.err;
  // A silent file gives a closed jaw, not an error.
  r = run_avar({"jaw", wav, "--rig", kJawRig, "--out", show_path});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const playback::Show show = config::load_show_file(show_path);
  for (const auto& key : show.tracks.at(0).raw.keys) EXPECT_EQ(key.value, 0.0);
}

}  // namespace
}  // namespace avar::app
