// The speech-band envelope of a voice: band-pass as the difference of two zero-phase
// Butterworth low-passes (no delay, so the lead is the only time shift), then a centred RMS.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "avar/playback/offline/jaw_from_audio.hpp"
#include "avar/playback/offline/smoothing.hpp"

namespace avar::playback {

void validate(const JawOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(o.band_low_hz > 0) || !(o.band_high_hz > o.band_low_hz)) fail("the speech band needs 0 < low < high (Hz)");
  if (!std::isfinite(o.gate_db) || !std::isfinite(o.full_db) || !(o.full_db > o.gate_db))
    fail("the full-open level (dBFS) must be above the gate level");
  if (!(o.hysteresis_db >= 0) || !std::isfinite(o.hysteresis_db)) fail("the gate hysteresis must be 0 dB or more");
  if (!(o.attack_s >= 0) || !(o.release_s >= 0) || !std::isfinite(o.attack_s) || !std::isfinite(o.release_s))
    fail("attack and release must be 0 s or more");
  if (!(o.curve > 0) || !std::isfinite(o.curve)) fail("the curve exponent must be above 0");
  if (!(o.frame_rate_hz > 0) || !std::isfinite(o.frame_rate_hz)) fail("the frame rate must be above 0 Hz");
  if (!std::isfinite(o.closed) || !std::isfinite(o.open)) fail("closed and open must be finite");
  if (!(o.lead_s >= 0) || !std::isfinite(o.lead_s)) fail("the lead must be 0 s or more");
}

std::vector<double> speech_envelope_db(std::span<const float> samples, double sample_rate_hz, const JawOptions& o) {
  validate(o);
  if (!(sample_rate_hz > 0)) throw std::invalid_argument("the sample rate must be above 0 Hz");
  const std::vector<double> x(samples.begin(), samples.end());
  std::vector<double> band = x;
  if (x.size() >= 2) {
    const double high = std::min(o.band_high_hz, 0.45 * sample_rate_hz);
    if (!(high > o.band_low_hz)) throw std::invalid_argument("the speech band lies above half the audio's sample rate");
    const std::vector<double> below_high = butterworth_zero_phase(x, sample_rate_hz, high, 4);
    const std::vector<double> below_low = butterworth_zero_phase(x, sample_rate_hz, o.band_low_hz, 4);
    for (std::size_t i = 0; i < band.size(); ++i) band[i] = below_high[i] - below_low[i];
  }
  // Prefix sums of squares: the RMS of any window in O(1).
  std::vector<double> energy(band.size() + 1, 0.0);
  for (std::size_t i = 0; i < band.size(); ++i) energy[i + 1] = energy[i] + band[i] * band[i];
  const double duration = static_cast<double>(samples.size()) / sample_rate_hz;
  const auto frames = static_cast<std::size_t>(std::floor(duration * o.frame_rate_hz)) + 1;
  const double half_window = sample_rate_hz / o.frame_rate_hz;  // samples either side
  std::vector<double> levels;
  levels.reserve(frames);
  for (std::size_t k = 0; k < frames; ++k) {
    const double centre = static_cast<double>(k) / o.frame_rate_hz * sample_rate_hz;
    const auto first =
        static_cast<std::size_t>(std::clamp(std::floor(centre - half_window), 0.0, static_cast<double>(band.size())));
    const auto last =
        static_cast<std::size_t>(std::clamp(std::ceil(centre + half_window), 0.0, static_cast<double>(band.size())));
    const double mean_square = last > first ? (energy[last] - energy[first]) / static_cast<double>(last - first) : 0.0;
    levels.push_back(10 * std::log10(std::max(mean_square, 1e-20)));
  }
  return levels;
}

}  // namespace avar::playback
