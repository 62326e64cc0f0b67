#include "avar/core/format.hpp"
#include "avar/config/show_file.hpp"

#include <filesystem>
#include <set>

#include "avar/config/yaml_support.hpp"

namespace avar::config {
namespace {

playback::Handle read_handle(const YamlRef& node, std::string_view what) {
  if (!node.is_sequence() || node.size() != 2)
    node.fail("expected " + std::string(what) + " to be [time, value], found " + node.describe());
  return {node[0].as_double(std::string(what) + " time"), node[1].as_double(std::string(what) + " value")};
}

playback::RawKey read_key(const YamlRef& node, double duration, const std::string& channel) {
  const std::string what = "a key of track '" + channel + "'";
  node.expect_only_keys({"time", "value", "interpolation", "left", "right"}, what);
  playback::RawKey key;
  key.where = node.where();
  const YamlRef time = node.at("time", what);
  key.time = time.as_double("the key time (seconds)");
  if (key.time < 0 || key.time > duration)
    time.fail("key time " + format_number(key.time) + " s is outside the show, which runs from 0 to " + format_number(duration) + " s");
  key.value = node.at("value", what).as_double("the key value");
  if (auto interp = node.find("interpolation")) {
    const auto parsed = playback::interpolation_from_name(interp->as_string("the interpolation"));
    if (!parsed) interp->fail("unknown interpolation " + interp->describe() + "; expected one of: step, linear, bezier");
    key.interpolation = *parsed;
  }
  if (auto left = node.find("left")) key.left = read_handle(*left, "the left handle");
  if (auto right = node.find("right")) key.right = read_handle(*right, "the right handle");
  return key;
}

}  // namespace

playback::Show load_show_file(const std::string& path) {
  const YAML::Node root_node = load_yaml_file(path);
  const YamlRef root{root_node, &path};
  root.expect_only_keys({"name", "duration", "loop", "tracks"}, "the show file");

  playback::Show show;
  show.where = {path, 1, 1};
  show.name = root.find("name") ? root.at("name", "the show file").as_string("the show's name")
                                : std::filesystem::path(path).stem().string();
  const YamlRef duration = root.at("duration", "the show file");
  show.duration = duration.as_double("the duration (seconds)");
  if (show.duration <= 0) duration.fail("expected the duration to be more than 0 seconds, found " + duration.describe());
  if (auto loop = root.find("loop")) show.loop = loop->as_bool("loop");

  const YamlRef tracks = root.at("tracks", "the show file");
  tracks.expect_map("tracks (a map of channel name to a list of keys)");
  std::set<std::string> seen;
  for (auto it = tracks.node.begin(); it != tracks.node.end(); ++it) {
    const YamlRef name{it->first, &path};
    const std::string channel = name.as_string("a channel name");
    if (!seen.insert(channel).second) name.fail("channel '" + channel + "' has two tracks; expected one track per channel");
    const YamlRef keys{it->second, &path};
    keys.expect_sequence("the keys of track '" + channel + "'");
    playback::Track track;
    track.channel = channel;
    track.where = name.where();
    track.raw.where = name.where();
    if (keys.size() == 0) name.fail("track '" + channel + "' has no keys; expected at least one");
    for (std::size_t i = 0; i < keys.size(); ++i) track.raw.keys.push_back(read_key(keys[i], show.duration, channel));
    track.curve = playback::Curve::build(track.raw);
    show.tracks.push_back(std::move(track));
  }
  return show;
}

}  // namespace avar::config
