// The jaw from audio on synthetic signals: tone bursts with silences, noise below the gate, the
// lead, the mapping onto the channel's range.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "avar/playback/offline/jaw_from_audio.hpp"

namespace avar::playback {
namespace {

constexpr double kJawRate = 16000;

/// A 1 kHz tone of `amplitude` during each [start, end) of `bursts`, silence elsewhere.
std::vector<float> jaw_tone_bursts(double duration, std::initializer_list<std::pair<double, double>> bursts, double amplitude) {
  std::vector<float> x(static_cast<std::size_t>(duration * kJawRate), 0.0f);
  for (const auto& [start, end] : bursts)
    for (auto i = static_cast<std::size_t>(start * kJawRate); i < static_cast<std::size_t>(end * kJawRate) && i < x.size(); ++i)
      x[i] = static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * 1000 * static_cast<double>(i) / kJawRate));
  return x;
}

double jaw_value_at(const JawMotion& m, double t) {
  const auto k = static_cast<std::size_t>(std::lround(t * 100));
  return m.values.at(k);
}

/// First time the value reaches `level` (channel units, opening upward), or -1.
double jaw_first_crossing(const JawMotion& m, double level, double after = 0) {
  for (std::size_t k = 0; k < m.values.size(); ++k)
    if (m.times[k] >= after && m.values[k] >= level) return m.times[k];
  return -1;
}

JawOptions jaw_options() {
  JawOptions o;
  o.closed = 2;
  o.open = 30;
  return o;
}

TEST(JawFromAudio, ToneBurstsOpenTheJawAndSilenceKeepsItExactlyClosed) {
  const auto audio = jaw_tone_bursts(3.0, {{0.5, 1.0}, {1.6, 2.1}}, 0.5);
  const JawMotion m = jaw_from_audio(audio, kJawRate, jaw_options());
  ASSERT_EQ(m.times.size(), m.values.size());
  EXPECT_NEAR(m.times.back(), 3.0, 0.011);
  for (std::size_t k = 0; k < m.values.size(); ++k) {
    const double t = m.times[k];
    EXPECT_GE(m.values[k], 2.0) << t;
    EXPECT_LE(m.values[k], 30.0) << t;
    // Before the first burst (the RMS window reaches 10 ms ahead) and well after each one.
    if (t < 0.48 || (t > 1.5 && t < 1.58) || t > 2.6) {
      EXPECT_EQ(m.values[k], 2.0) << "silence moved the jaw at " << t << " s";
    }
  }
  // A -9 dBFS tone (above full_db -12) opens the jaw fully within a few attack constants.
  EXPECT_GT(jaw_value_at(m, 0.8), 29.0);
  EXPECT_GT(jaw_value_at(m, 1.9), 29.0);
  // Between the bursts it closes.
  EXPECT_LT(jaw_value_at(m, 1.45), 3.0);
}

TEST(JawFromAudio, NoiseBelowTheGateNeverMovesTheJaw) {
  std::mt19937 rng(20261203);
  std::normal_distribution<double> noise(0, 0.004);  // about -48 dBFS, in band lower still: under the -40 dB gate
  std::vector<float> audio(static_cast<std::size_t>(2 * kJawRate));
  for (float& s : audio) s = static_cast<float>(noise(rng));
  const JawMotion m = jaw_from_audio(audio, kJawRate, jaw_options());
  for (std::size_t k = 0; k < m.values.size(); ++k) {
    EXPECT_LT(m.envelope_db[k], -40.0);
    EXPECT_EQ(m.values[k], 2.0) << m.times[k];
  }
}

TEST(JawFromAudio, GateHysteresisHoldsThroughADipAboveTheClosingLevel) {
  JawOptions o = jaw_options();
  // Levels: opens at -40, holds while above -46, closes below.
  const std::vector<double> levels = {-80, -39, -30, -44, -44, -30, -47, -47, -47, -80};
  o.attack_s = 0;
  o.release_s = 0;
  const std::vector<double> open = gated_opening(levels, o);
  EXPECT_EQ(open[0], 0);
  EXPECT_GT(open[1], 0);
  EXPECT_GT(open[3], 0) << "a dip above the closing level keeps the gate open";
  EXPECT_EQ(open[6], 0);
  // -44 dB with a gate that was never opened stays shut.
  const std::vector<double> quiet = {-44, -44, -44};
  for (const double v : gated_opening(quiet, o)) EXPECT_EQ(v, 0);
}

TEST(JawFromAudio, LeadMovesTheOpeningEarlierByTheConfiguredTime) {
  const auto audio = jaw_tone_bursts(2.0, {{0.7, 1.2}}, 0.5);
  JawOptions o = jaw_options();
  const JawMotion plain = jaw_from_audio(audio, kJawRate, o);
  o.lead_s = 0.12;
  const JawMotion led = jaw_from_audio(audio, kJawRate, o);
  const double mid = 16;
  const double t_plain = jaw_first_crossing(plain, mid);
  const double t_led = jaw_first_crossing(led, mid);
  ASSERT_GT(t_plain, 0.69);
  EXPECT_NEAR(t_plain - t_led, 0.12, 0.011);
  // The envelope itself is not shifted: it crosses the gate at the burst onset.
  std::size_t onset = 0;
  while (led.envelope_db[onset] < o.gate_db) ++onset;
  EXPECT_NEAR(led.times[onset], 0.7, 0.011);
  EXPECT_LT(t_led, led.times[onset]) << "with a lead the jaw moves before the sound";
}

TEST(JawFromAudio, CurveMapsOntoAnInvertedRange) {
  const auto audio = jaw_tone_bursts(1.0, {{0.2, 0.8}}, 0.05);  // -29 dBFS: partly open
  JawOptions o;
  o.closed = 90;
  o.open = 60;
  o.curve = 1;
  const JawMotion linear = jaw_from_audio(audio, kJawRate, o);
  o.curve = 0.5;
  const JawMotion rooted = jaw_from_audio(audio, kJawRate, o);
  const double a = jaw_value_at(linear, 0.5), b = jaw_value_at(rooted, 0.5);
  EXPECT_LT(a, 90);
  EXPECT_GT(a, 60);
  EXPECT_LT(b, a) << "a curve below 1 opens more on a quiet voice";
  const double opening = (90 - a) / 30;
  EXPECT_NEAR((90 - b) / 30, std::sqrt(opening), 1e-9);
}

TEST(JawFromAudio, TimeToHalfOpenFollowsTheTrapezoid) {
  // Triangle: 10 units at 100 units/s^2, speed never reached: 2 sqrt(10 / 100) = 0.632 s.
  EXPECT_NEAR(time_to_half_open(10, 1000, 100), std::sqrt(0.1), 1e-12);
  // Trapezoid: 30 at 60 units/s, 600 units/s^2: 0.5 + 0.1 = 0.6 s, half 0.3 s.
  EXPECT_NEAR(time_to_half_open(-30, 60, 600), 0.3, 1e-12);
}

TEST(JawFromAudio, RejectsOptionsOutOfRange) {
  JawOptions o;
  o.band_high_hz = 100;
  EXPECT_THROW(validate(o), std::invalid_argument);
  o = JawOptions{};
  o.full_db = -50;
  EXPECT_THROW(validate(o), std::invalid_argument);
  o = JawOptions{};
  o.lead_s = -0.1;
  EXPECT_THROW(validate(o), std::invalid_argument);
  const std::vector<float> empty;
  const JawMotion m = jaw_from_audio(empty, 8000, JawOptions{});
  ASSERT_EQ(m.values.size(), 1u);
  EXPECT_EQ(m.values[0], 0);
}

}  // namespace
}  // namespace avar::playback
