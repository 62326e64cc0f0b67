#pragma once
// A jaw's motion from speech audio, offline (the "talking figure" of animatronics: the mouth
// follows the loudness of the voice). Pure signal processing on mono samples, no file I/O:
//
//   samples ─► speech band (zero-phase Butterworth band-pass, lo-hi Hz)
//           ─► envelope (RMS over a window of 2 frames, centred on each frame, in dBFS; a full-scale
//              sine is -3 dBFS)
//           ─► noise gate with hysteresis (opens at gate_db, closes below gate_db - hysteresis_db;
//              closed: the opening is exactly 0)
//           ─► opening in [0, 1]: (level - close level) / (full_db - close level), clamped
//           ─► attack / release (one pole each, time constants in seconds; closing aims 5% below
//              closed and stops at closed, so silence closes the jaw exactly, in about 3
//              release constants from fully open)
//           ─► curve: opening^curve, mapped onto [closed, open] in channel units
//           ─► lead: the motion comes `lead_s` earlier than the sound (value at t is the value of
//              t + lead_s), so that a servo that lags by lead_s opens the mouth on the syllable.
//
// Load time: allocates, throws std::invalid_argument on options out of range.

#include <span>
#include <string>
#include <vector>

namespace avar::playback {

struct JawOptions {
  double band_low_hz = 300;    ///< speech band, > 0
  double band_high_hz = 3000;  ///< > band_low_hz; lowered to 0.45 x the sample rate if above it
  double gate_db = -40;        ///< envelope level (dBFS) at which the gate opens
  double hysteresis_db = 6;    ///< the gate closes below gate_db - hysteresis_db, >= 0
  double full_db = -12;        ///< envelope level (dBFS) at which the jaw is fully open, > gate_db
  double attack_s = 0.025;     ///< opening time constant, >= 0 (0: instant)
  double release_s = 0.080;    ///< closing time constant, >= 0
  double curve = 0.7;          ///< exponent of the opening, > 0 (< 1 opens more on quiet syllables)
  double frame_rate_hz = 100;  ///< envelope frames per second, > 0
  double closed = 0;           ///< channel value of the closed mouth
  double open = 1;             ///< channel value of the fully open mouth (may be below closed)
  double lead_s = 0;           ///< seconds the motion comes before the sound, >= 0
};

/// The speech-band envelope of `samples`, one level (dBFS) per frame at t_k = k / frame_rate_hz
/// for every frame within the audio. Precondition: sample_rate_hz > 0.
std::vector<double> speech_envelope_db(std::span<const float> samples, double sample_rate_hz, const JawOptions& options);

/// The opening (0 closed, 1 fully open) of each envelope frame after the gate and the
/// attack/release smoothing (before the curve and the lead).
std::vector<double> gated_opening(std::span<const double> envelope_db, const JawOptions& options);

struct JawMotion {
  std::vector<double> times;        ///< seconds, t_k = k / frame_rate_hz, covering the whole audio
  std::vector<double> values;       ///< channel units, within [min(closed, open), max(closed, open)]
  std::vector<double> envelope_db;  ///< the envelope of each frame, before the lead
};

/// The whole pipeline above. An empty input, or one shorter than a frame, gives one closed
/// sample at 0 s.
JawMotion jaw_from_audio(std::span<const float> samples, double sample_rate_hz, const JawOptions& options);

/// Throws std::invalid_argument naming the first option out of range.
void validate(const JawOptions& options);

/// Rest-to-rest move time over `distance` at speed and acceleration limits (trapezoid, or
/// triangle when the speed is never reached), halved: when the mouth reads as open. Seconds.
double time_to_half_open(double distance, double max_velocity, double max_acceleration);

}  // namespace avar::playback
