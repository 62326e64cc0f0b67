#include "show_visemes.hpp"

#include <algorithm>
#include <filesystem>

#include "avar/config/viseme_cues.hpp"
#include "avar/config/viseme_tracks.hpp"
#include "avar/core/format.hpp"
#include "viseme_table.hpp"

namespace avar::config::detail {

void read_show_visemes(const YamlRef& node, playback::Show& show) {
  const std::string what = "the show's visemes";
  node.expect_map(what + " (a map {file, table, fps, start, rise_ms, decay_ms, tolerance})");
  node.expect_only_keys({"file", "table", "fps", "start", "rise_ms", "decay_ms", "tolerance"}, what);
  const YamlRef file = node.at("file", what + " (file: Rhubarb TSV or JSON, or a Papagayo/Moho .dat, relative to the show file)");
  std::filesystem::path path = file.as_string("the mouth-cue file's path");
  if (path.is_relative()) path = std::filesystem::path(*node.file).parent_path() / path;
  const playback::VisemeTable table =
      read_viseme_table(node.at("table", what + " (table: mouth shape -> pose)"), "the visemes table");
  const auto positive = [&](const char* key, const char* unit, double fallback) {
    const auto v = node.find(key);
    if (!v) return fallback;
    const double x = v->as_double(std::string(key) + " (" + unit + ")");
    if (!(x > 0)) v->fail("expected " + std::string(key) + " to be above 0, found " + v->describe());
    return x;
  };
  const double fps = positive("fps", "frames per second of a Moho switch file", 24);
  playback::CoarticulationOptions blend;
  blend.rise_s = positive("rise_ms", "milliseconds of anticipation", blend.rise_s * 1000) / 1000;
  blend.decay_s = positive("decay_ms", "milliseconds of carry-over", blend.decay_s * 1000) / 1000;
  std::optional<double> tolerance;
  if (node.has("tolerance")) tolerance = positive("tolerance", "channel units", 1);
  double start = 0;
  if (auto s = node.find("start")) {
    start = s->as_double("start (show seconds where the cues begin)");
    if (start < 0 || start >= show.duration)
      s->fail("cue start " + format_number(start) + " s is outside the show, which runs from 0 to " +
              format_number(show.duration) + " s");
  }
  const auto table_node = node.at("table", what);
  for (const std::string& channel : table.channels)
    if (std::any_of(show.tracks.begin(), show.tracks.end(), [&](const playback::Track& t) { return t.channel == channel; }))
      table_node.fail("channel '" + channel + "' has a track and is posed by the visemes table; expected one or the other");
  const auto cues = read_viseme_cues(path.string(), fps, file.where());
  for (playback::Track& track : viseme_tracks(cues, table, blend, start, show.duration, tolerance, file.where())) {
    track.where = node.where();
    show.tracks.push_back(std::move(track));
  }
}

}  // namespace avar::config::detail
