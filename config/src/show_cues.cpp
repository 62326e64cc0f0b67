#include "show_cues.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <map>

#include "avar/firmware_iface/udp_destination.hpp"
#include "avar/core/format.hpp"
#include "show_tracks.hpp"

namespace avar::config::detail {
namespace {

/// A scalar argument: a whole number is an OSC int, another number a float, anything else a string.
playback::CueArgument read_cue_argument(const YamlRef& node, const std::string& what) {
  const ScalarValue v = node.scalar();
  if (!v.scalar) node.fail("expected " + what + " to be a number or a string, found " + node.describe());
  playback::CueArgument a;
  const std::string& text = v.text;
  char* end = nullptr;
  errno = 0;
  const long long whole = std::strtoll(text.c_str(), &end, 10);
  if (!text.empty() && *end == '\0' && errno == 0 && whole >= -2147483648LL && whole <= 2147483647LL) {
    a.type = 'i';
    a.number = static_cast<double>(whole);
    return a;
  }
  const double x = std::strtod(text.c_str(), &end);
  if (!text.empty() && *end == '\0' && std::isfinite(x)) {
    a.type = 'f';
    a.number = x;
    return a;
  }
  a.type = 's';
  a.text = text;
  return a;
}

void read_osc_cue(const YamlRef& body, const std::string& what, playback::Cue& cue) {
  body.expect_map("the osc of " + what + " ({to: HOST:PORT, address: /path, args: [...]})");
  body.expect_only_keys({"to", "address", "args"}, "the osc of " + what);
  const YamlRef to = body.at("to", "the osc of " + what);
  const std::string text = to.as_string("the OSC destination (HOST:PORT)");
  try {
    const firmware_iface::UdpDestination d = firmware_iface::parse_udp_destination(text, 0);
    if (text.find(':') == std::string::npos) to.fail("expected HOST:PORT for the OSC destination, found " + to.describe());
    cue.osc_host = d.host;
    cue.osc_port = d.port;
  } catch (const std::invalid_argument& e) {
    to.fail(e.what());
  }
  const YamlRef address = body.at("address", "the osc of " + what);
  cue.osc_address = address.as_string("the OSC address");
  if (cue.osc_address.front() != '/' || cue.osc_address.find_first_of(" #*,?[]{}") != std::string::npos)
    address.fail("expected an OSC address such as /lights/go (starting with /, no spaces or # * , ? [ ] { }), found " +
                 address.describe());
  if (auto args = body.find("args")) {
    args->expect_sequence("the args of " + what + " (a list of numbers and strings)");
    for (std::size_t i = 0; i < args->size(); ++i)
      cue.osc_arguments.push_back(read_cue_argument((*args)[i], "argument " + std::to_string(i + 1) + " of " + what));
  }
}

void read_digital_cue(const YamlRef& body, const std::string& what, playback::Cue& cue) {
  body.expect_map("the digital of " + what + " ({channel: NAME, value: 0|1})");
  body.expect_only_keys({"channel", "value"}, "the digital of " + what);
  cue.digital_channel = body.at("channel", "the digital of " + what).as_string("the channel of " + what);
  const YamlRef value = body.at("value", "the digital of " + what);
  const long long v = value.as_integer("the value of " + what + " (0 off, 1 on)");
  if (v != 0 && v != 1) value.fail("expected the value of " + what + " to be 0 (off) or 1 (on), found " + value.describe());
  cue.digital_value = static_cast<double>(v);
}

}  // namespace

void read_cues(const YamlRef& list, playback::Show& show) {
  list.expect_sequence("cues (a list of {time, osc: {...}} or {time, digital: {...}})");
  std::map<std::string, std::vector<const playback::Cue*>> by_channel;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YamlRef node = list[i];
    const std::string what = "cue " + std::to_string(i + 1);
    node.expect_map(what + " ({time, osc: {...}} or {time, digital: {...}})");
    node.expect_only_keys({"time", "osc", "digital"}, what);
    playback::Cue cue;
    cue.where = node.where();
    cue.time = read_key_time(node, what);
    // Keys may lie outside the played span (they shape the curve inside it); a cue outside it
    // would never fire.
    if (cue.time < 0 || cue.time > show.duration)
      node.at("time", what)
          .fail(what + " at " + format_number(cue.time) + " s never fires: the show runs from 0 to " +
                format_number(show.duration) + " s");
    const auto osc = node.find("osc");
    const auto digital = node.find("digital");
    if (osc.has_value() == digital.has_value())
      node.fail("expected " + what + " to have exactly one of osc: {...} or digital: {...}");
    if (osc) read_osc_cue(*osc, what, cue);
    else read_digital_cue(*digital, what, cue);
    show.cues.push_back(std::move(cue));
  }
  std::stable_sort(show.cues.begin(), show.cues.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  for (const playback::Cue& c : show.cues)
    if (!c.is_osc()) by_channel[c.digital_channel].push_back(&c);

  // Each cued digital channel becomes a step track: off until its first cue.
  for (const auto& [channel, cues] : by_channel) {
    const playback::Cue& first = *cues.front();
    for (const playback::Track& t : show.tracks)
      if (t.channel == channel)
        YamlRef{list.node, list.file}.fail("channel '" + channel + "' has a track and digital cues (the first at " +
                                           std::to_string(first.where.line) + ":" + std::to_string(first.where.column) +
                                           "); expected one or the other");
    playback::Track track;
    track.channel = channel;
    track.where = first.where;
    track.raw.where = first.where;
    if (first.time > 0) {
      playback::RawKey off;
      off.value = 0;
      off.interpolation = playback::Interpolation::step;
      off.where = first.where;
      track.raw.keys.push_back(off);
    }
    for (const playback::Cue* c : cues) {
      if (!track.raw.keys.empty() && track.raw.keys.back().time == c->time && c != &first)
        throw InputError(c->where, "channel '" + channel + "' has two digital cues at " + std::to_string(c->time) +
                                       " s; expected one cue per channel and time");
      playback::RawKey key;
      key.time = c->time;
      key.value = c->digital_value;
      key.interpolation = playback::Interpolation::step;
      key.where = c->where;
      track.raw.keys.push_back(key);
    }
    track.curve = playback::Curve::build(track.raw);
    show.tracks.push_back(std::move(track));
  }
}

void read_markers(const YamlRef& list, playback::Show& show) {
  list.expect_sequence("markers (a list of {time, name})");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YamlRef node = list[i];
    const std::string what = "marker " + std::to_string(i + 1);
    node.expect_map(what + " ({time: SECONDS, name: TEXT})");
    node.expect_only_keys({"time", "name"}, what);
    playback::Marker marker;
    marker.where = node.where();
    marker.time = read_key_time(node, what);
    if (marker.time < 0 || marker.time > show.duration)
      node.at("time", what)
          .fail("expected " + what + " within the show, from 0 to " + format_number(show.duration) + " s, found " +
                format_number(marker.time) + " s");
    const YamlRef name = node.at("name", what);
    marker.name = name.as_string("the name of " + what);  // refuses an empty one
    for (const playback::Marker& other : show.markers)
      if (other.name == marker.name)
        name.fail("marker name '" + marker.name + "' is used twice (first at line " + std::to_string(other.where.line) +
                  "); expected each marker named once");
    show.markers.push_back(std::move(marker));
  }
  std::stable_sort(show.markers.begin(), show.markers.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
}

}  // namespace avar::config::detail
