#include "viseme_table.hpp"

#include <algorithm>

#include "avar/core/format.hpp"

namespace avar::config::detail {

playback::VisemeTable read_viseme_table(const YamlRef& node, std::string_view what) {
  const std::string twhat = std::string(what) + " (a map of mouth shape to a pose {channel: value, ..., dominance: weight})";
  node.expect_map(twhat);
  if (node.size() == 0) node.fail("expected at least one mouth shape in " + std::string(what) + ", found none");
  playback::VisemeTable table;
  table.where = node.where();
  for (auto it = node.node.begin(); it != node.node.end(); ++it) {
    const YamlRef shape{it->first, node.file};
    const YamlRef pose{it->second, node.file};
    const std::string name = shape.as_string("a mouth shape");
    if (table.find(name) != table.shapes.size()) shape.fail("mouth shape '" + name + "' appears twice; expected each shape once");
    pose.expect_map("the pose of mouth shape '" + name + "' ({channel: value, ...})");
    std::vector<std::pair<std::string, double>> values;
    double dominance = 1;
    for (auto p = pose.node.begin(); p != pose.node.end(); ++p) {
      const YamlRef key{p->first, node.file};
      const YamlRef value{p->second, node.file};
      const std::string channel = key.as_string("a channel name");
      if (channel == "dominance") {
        dominance = value.as_double("the dominance of mouth shape '" + name + "'");
        if (!(dominance > 0))
          value.fail("expected the dominance of mouth shape '" + name + "' to be above 0, found " + value.describe());
        continue;
      }
      values.emplace_back(channel, value.as_double("the value of channel '" + channel + "' in mouth shape '" + name + "'"));
    }
    if (values.empty()) pose.fail("the pose of mouth shape '" + name + "' names no channel; expected {channel: value, ...}");
    if (table.shapes.empty())
      for (const auto& [channel, v] : values) table.channels.push_back(channel);
    std::vector<double> ordered(table.channels.size());
    for (std::size_t c = 0; c < table.channels.size(); ++c) {
      const auto found =
          std::find_if(values.begin(), values.end(), [&](const auto& cv) { return cv.first == table.channels[c]; });
      if (found == values.end())
        pose.fail("the pose of mouth shape '" + name + "' has no value for channel '" + table.channels[c] +
                  "'; expected every pose to set the same channels as the first ('" + table.shapes.front() + "')");
      ordered[c] = found->second;
    }
    if (values.size() != table.channels.size())
      pose.fail("the pose of mouth shape '" + name + "' sets a channel the first pose ('" + table.shapes.front() +
                "') does not; expected every pose to set the same channels");
    table.shapes.push_back(name);
    table.poses.push_back(ordered);
    table.dominance.push_back(dominance);
  }
  return table;
}

playback::VisemeTable read_rig_viseme_table(const YamlRef& node, const rig::Rig& rig) {
  // Channel names first: an unknown channel is a clearer message than a pose that differs.
  if (node.is_map())
    for (auto it = node.node.begin(); it != node.node.end(); ++it)
      if (it->second.IsMap())
        for (auto p = it->second.begin(); p != it->second.end(); ++p)
          if (p->first.Scalar() != "dominance" && !rig.find_channel(p->first.Scalar()))
            YamlRef{p->first, node.file}.fail("mouth shape '" + it->first.Scalar() + "' poses channel '" + p->first.Scalar() +
                                              "', which the rig does not have; expected one of its channels");
  playback::VisemeTable table = read_viseme_table(node, "the rig's visemes table");
  for (auto it = node.node.begin(); it != node.node.end(); ++it) {
    const std::string shape = it->first.Scalar();
    for (auto p = it->second.begin(); p != it->second.end(); ++p) {
      const std::string name = p->first.Scalar();
      if (name == "dominance") continue;
      const rig::ChannelSpec& ch = rig.channels[*rig.find_channel(name)];
      const double v = p->second.as<double>();
      if (v < ch.min || v > ch.max)
        YamlRef{p->second, node.file}.fail("mouth shape '" + shape + "' sets '" + name + "' to " + format_number(v) + " " +
                                           ch.unit + "; expected within its limits [" + format_number(ch.min) + ", " +
                                           format_number(ch.max) + "]");
    }
  }
  return table;
}

}  // namespace avar::config::detail
