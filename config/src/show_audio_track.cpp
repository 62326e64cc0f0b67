#include "show_audio_track.hpp"

#include <filesystem>

#include "avar/config/jaw_track.hpp"
#include "avar/core/format.hpp"

namespace avar::config::detail {

playback::Track read_audio_track(const YamlRef& name, const YamlRef& audio, double duration) {
  const std::string channel = name.as_string("a channel name");
  const std::string what = "the audio source of track '" + channel + "'";
  audio.expect_map(what +
                   " (a map {file, open, closed, start, lead_ms, gate_db, full_db, hysteresis_db, attack_ms, release_ms, "
                   "band_hz, curve, tolerance})");
  audio.expect_only_keys({"file", "open", "closed", "start", "lead_ms", "gate_db", "full_db", "hysteresis_db", "attack_ms",
                          "release_ms", "band_hz", "curve", "tolerance"},
                         what);
  const YamlRef file = audio.at("file", what + " (file: a WAV, FLAC or OGG file, relative to the show file)");
  std::filesystem::path path = file.as_string("the sound file's path");
  if (path.is_relative()) path = std::filesystem::path(*audio.file).parent_path() / path;

  playback::JawOptions o;
  o.open = audio.at("open", what + " (open: the channel value of the open mouth)").as_double("the open mouth (channel units)");
  if (auto v = audio.find("closed")) o.closed = v->as_double("the closed mouth (channel units)");
  if (o.open == o.closed)
    audio.at("open", what)
        .fail("the open mouth equals the closed one (" + format_number(o.closed) + "); expected a different value");
  const auto non_negative = [&](const char* key, const char* unit, double scale, double& out) {
    const auto v = audio.find(key);
    if (!v) return;
    const double x = v->as_double(std::string(key) + " (" + unit + ")");
    if (x < 0) v->fail("expected " + std::string(key) + " to be 0 or more, found " + v->describe());
    out = x * scale;
  };
  double start = 0;
  non_negative("start", "show seconds where the audio begins", 1, start);
  non_negative("lead_ms", "milliseconds the jaw moves before the sound", 0.001, o.lead_s);
  non_negative("attack_ms", "milliseconds", 0.001, o.attack_s);
  non_negative("release_ms", "milliseconds", 0.001, o.release_s);
  non_negative("hysteresis_db", "dB", 1, o.hysteresis_db);
  if (auto v = audio.find("gate_db")) o.gate_db = v->as_double("the gate level (dBFS)");
  if (auto v = audio.find("full_db")) o.full_db = v->as_double("the full-open level (dBFS)");
  if (!(o.full_db > o.gate_db))
    audio.fail("expected full_db (" + format_number(o.full_db) + ") above gate_db (" + format_number(o.gate_db) + ") in " + what);
  if (auto v = audio.find("curve")) {
    o.curve = v->as_double("the curve exponent");
    if (!(o.curve > 0)) v->fail("expected the curve exponent to be above 0, found " + v->describe());
  }
  if (auto band = audio.find("band_hz")) {
    band->expect_sequence("the speech band ([low, high] in Hz)");
    if (band->size() != 2)
      band->fail("expected the speech band [low, high] in Hz, found " + std::to_string(band->size()) + " numbers");
    o.band_low_hz = (*band)[0].as_double("the band's low edge (Hz)");
    o.band_high_hz = (*band)[1].as_double("the band's high edge (Hz)");
    if (!(o.band_low_hz > 0) || !(o.band_high_hz > o.band_low_hz))
      band->fail("expected 0 < low < high in the speech band, found [" + format_number(o.band_low_hz) + ", " +
                 format_number(o.band_high_hz) + "]");
  }
  double tolerance = default_jaw_tolerance(o);
  if (auto v = audio.find("tolerance")) {
    tolerance = v->as_double("the fitting tolerance (channel units)");
    if (!(tolerance > 0)) v->fail("expected the fitting tolerance to be above 0, found " + v->describe());
  }
  if (start >= duration)
    audio.at("start", what)
        .fail("audio start " + format_number(start) + " s is outside the show, which runs from 0 to " + format_number(duration) +
              " s");
  playback::Track track = jaw_track_from_audio(path.string(), channel, o, tolerance, file.where(), start, duration).track;
  track.where = name.where();
  track.raw.where = name.where();
  track.raw.audio = playback::AudioSource{path.string(), start};
  return track;
}

}  // namespace avar::config::detail
