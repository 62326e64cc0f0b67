#include "avar/config/viseme_cues.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "avar/core/format.hpp"

namespace avar::config {
namespace {

struct CueWord {
  std::string text;
  int column = 1;
};

/// The whitespace-separated words of a line, with their 1-based columns.
std::vector<CueWord> cue_words(const std::string& line) {
  std::vector<CueWord> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return words;
}

double cue_number(const std::string& path, int line, const CueWord& w, const char* expected) {
  double v = 0;
  const auto [ptr, ec] = std::from_chars(w.text.data(), w.text.data() + w.text.size(), v);
  if (ec != std::errc() || ptr != w.text.data() + w.text.size() || !std::isfinite(v) || v < 0)
    throw InputError({path, line, w.column}, "found '" + w.text + "'; expected " + expected);
  return v;
}

/// Closes each cue at the next one's start; the last is held for no time.
void chain_cues(std::vector<playback::VisemeCue>& cues) {
  for (std::size_t i = 0; i < cues.size(); ++i) cues[i].end = i + 1 < cues.size() ? cues[i + 1].start : cues[i].start;
}

/// Text formats: Rhubarb TSV (`seconds shape`) or, after a MohoSwitch1 line, `frame phoneme`.
std::vector<playback::VisemeCue> read_line_cues(const std::string& path, std::istream& in, double fps) {
  std::vector<playback::VisemeCue> cues;
  bool moho = false, first = true;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto words = cue_words(line);
    if (words.empty()) continue;
    if (first && words[0].text == "MohoSwitch1") {
      moho = true;
      first = false;
      continue;
    }
    first = false;
    if (words.size() != 2)
      throw InputError({path, number, words[0].column},
                       "found " + std::to_string(words.size()) + " fields; expected " +
                           (moho ? "'frame phoneme' (a Papagayo/Moho switch line)" : "'seconds<TAB>shape' (a Rhubarb TSV line)"));
    playback::VisemeCue cue;
    cue.where = {path, number, words[0].column};
    if (moho) {
      const double frame = cue_number(path, number, words[0], "a frame number of 1 or more");
      if (frame < 1 || frame != std::floor(frame))
        throw InputError(cue.where, "found frame '" + words[0].text + "'; expected a whole frame number of 1 or more");
      cue.start = (frame - 1) / fps;
    } else {
      cue.start = cue_number(path, number, words[0], "a time in seconds (0 or more)");
    }
    cue.shape = words[1].text;
    if (!cues.empty() && cue.start < cues.back().start)
      throw InputError(cue.where, "cue at " + format_number(cue.start) + " s comes before the previous one at " +
                                      format_number(cues.back().start) + " s; expected times in order");
    cues.push_back(cue);
  }
  chain_cues(cues);
  return cues;
}

std::vector<playback::VisemeCue> read_json_cues(const std::string& path, const std::string& text) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts from 1 and points just past the offending character.
    throw InputError(location_at(path, text, e.byte > 0 ? e.byte - 1 : 0), "not valid JSON; expected Rhubarb's JSON output");
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond a double's range (the message quotes it): located at its first occurrence.
    const std::string what = e.what();
    const auto open = what.find('\'');
    const auto close = open == std::string::npos ? open : what.find('\'', open + 1);
    const std::string token = close == std::string::npos ? std::string() : what.substr(open + 1, close - open - 1);
    const auto at = token.empty() ? std::string::npos : text.find(token);
    throw InputError(location_at(path, text, at == std::string::npos ? 0 : at),
                     "number " + (token.empty() ? std::string("out of range") : "'" + token + "' out of range") +
                         "; expected a time in seconds");
  }
  if (!doc.is_object() || !doc.contains("mouthCues") || !doc["mouthCues"].is_array())
    throw InputError(
        {path, 1, 1},
        "found no 'mouthCues' list; expected Rhubarb's JSON output {\"mouthCues\": [{\"start\", \"end\", \"value\"}]}");
  std::vector<playback::VisemeCue> cues;
  const auto& list = doc["mouthCues"];
  cues.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto& c = list[i];
    const std::string what = "mouthCues[" + std::to_string(i) + "]";
    const auto number = [&](const char* key) {
      if (!c.is_object() || !c.contains(key) || !c[key].is_number())
        throw InputError({path, 0, 0},
                         what + " has no number '" + key + "'; expected {\"start\": s, \"end\": s, \"value\": shape}");
      return c[key].get<double>();
    };
    playback::VisemeCue cue;
    cue.where = {path + " " + what, 0, 0};
    cue.start = number("start");
    cue.end = number("end");
    if (!c.contains("value") || !c["value"].is_string() || c["value"].get<std::string>().empty())
      throw InputError({path, 0, 0}, what + " has no shape 'value'; expected a mouth shape such as \"A\"");
    cue.shape = c["value"].get<std::string>();
    if (!(cue.start >= 0) || !(cue.end >= cue.start) || !std::isfinite(cue.end))
      throw InputError({path, 0, 0}, what + " runs from " + format_number(cue.start) + " to " + format_number(cue.end) +
                                         " s; expected 0 <= start <= end");
    if (!cues.empty() && cue.start < cues.back().start)
      throw InputError({path, 0, 0}, what + " starts before the cue before it; expected cues in time order");
    cues.push_back(cue);
  }
  return cues;
}

}  // namespace

std::vector<playback::VisemeCue> read_viseme_cues(const std::string& path, double fps, const SourceLocation& where) {
  if (!(fps > 0) || !std::isfinite(fps))
    throw InputError(where, "expected frames per second above 0, found " + format_number(fps));
  std::ifstream file(path);
  if (!file)
    throw InputError(where, "cannot open mouth-cue file '" + path +
                                "'; expected a Rhubarb TSV or JSON file or a Papagayo/Moho switch file (.dat)");
  std::stringstream text;
  text << file.rdbuf();
  const std::string all = text.str();
  const auto first = all.find_first_not_of(" \t\r\n");
  std::istringstream in(all);
  std::vector<playback::VisemeCue> cues =
      first != std::string::npos && all[first] == '{' ? read_json_cues(path, all) : read_line_cues(path, in, fps);
  if (cues.empty()) throw InputError({path, 1, 1}, "found no mouth cues; expected at least one");
  return cues;
}

}  // namespace avar::config
