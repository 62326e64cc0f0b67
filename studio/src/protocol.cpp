#include "avar/studio/protocol.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "avar/config/show_file.hpp"
#include "avar/core/input_error.hpp"

namespace avar::studio {
namespace {

using nlohmann::json;

/// A JSON object being read, named in every error ("message 'hold'", "edit 2 of message 'edit'").
class Fields {
 public:
  Fields(const json& object, std::string what) : object_(object), what_(std::move(what)) {
    if (!object_.is_object()) fail("expected a JSON object, found " + kind(object_));
  }

  [[noreturn]] void fail(const std::string& problem) const { throw ProtocolError(what_ + ": " + problem); }

  void expect_only(std::initializer_list<std::string_view> allowed) const {
    for (const auto& [name, value] : object_.items()) {
      if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
      std::string list;
      for (const std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail("unknown field '" + name + "'; expected only: " + list);
    }
  }
  const json& at(const char* name, const std::string& expected) const {
    const auto found = object_.find(name);
    if (found == object_.end()) fail("missing field '" + std::string(name) + "' (" + expected + ")");
    return *found;
  }
  double number(const char* name, const std::string& expected) const {
    const json& v = at(name, expected);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail("field '" + std::string(name) + "': expected " + expected + ", a finite number; found " + kind(v));
    return v.get<double>();
  }
  std::string text(const char* name, const std::string& expected) const {
    const json& v = at(name, expected);
    if (!v.is_string()) fail("field '" + std::string(name) + "': expected " + expected + ", a string; found " + kind(v));
    return v.get<std::string>();
  }
  bool boolean(const char* name, const std::string& expected) const {
    const json& v = at(name, expected);
    if (!v.is_boolean()) fail("field '" + std::string(name) + "': expected " + expected + ", true or false; found " + kind(v));
    return v.get<bool>();
  }
  std::size_t index(const json& v, const std::string& field) const {
    if (!v.is_number_unsigned()) fail(field + ": expected a key index (0, 1, ...), found " + kind(v));
    return v.get<std::size_t>();
  }
  const json& array(const char* name, const std::string& expected) const {
    const json& v = at(name, expected);
    if (!v.is_array()) fail("field '" + std::string(name) + "': expected " + expected + ", a list; found " + kind(v));
    return v;
  }
  const std::string& what() const { return what_; }

  static std::string kind(const json& v) {
    if (v.is_string()) return "the string \"" + v.get<std::string>() + "\"";
    if (v.is_number()) return "the number " + v.dump();
    if (v.is_boolean()) return v.dump();
    if (v.is_null()) return "null";
    return v.is_array() ? "a list" : "an object";
  }

 private:
  const json& object_;
  std::string what_;
};

std::size_t channel_index(const Fields& f, const std::string& name, const std::vector<std::string>& channels) {
  const auto found = std::find(channels.begin(), channels.end(), name);
  if (found != channels.end()) return static_cast<std::size_t>(found - channels.begin());
  std::string list;
  for (const std::string& c : channels) list += (list.empty() ? "" : ", ") + c;
  f.fail("no channel '" + name + "' in the rig; expected one of: " + list);
}

std::uint32_t target_index(const Fields& f, const std::string& name, const std::vector<std::string>& targets) {
  const auto found = std::find(targets.begin(), targets.end(), name);
  if (found != targets.end()) return static_cast<std::uint32_t>(found - targets.begin());
  if (targets.empty()) f.fail("field 'target': the show has no targets to aim ('" + name + "' asked)");
  std::string list;
  for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
  f.fail("no target '" + name + "' in the show; expected one of: " + list);
}

/// "point": [x, y, z], metres.
std::array<double, 3> point(const Fields& f) {
  const json& v = f.array("point", "[x, y, z] in metres, the rig's base frame");
  if (v.size() != 3) f.fail("field 'point': expected [x, y, z] in metres, three numbers; found " + std::to_string(v.size()));
  std::array<double, 3> p{};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!v[a].is_number() || !std::isfinite(v[a].get<double>()))
      f.fail("field 'point': expected [x, y, z] in metres, finite numbers; found " + Fields::kind(v[a]));
    p[a] = v[a].get<double>();
  }
  return p;
}

std::string channel(const Fields& f, const std::vector<std::string>& channels) {
  std::string name = f.text("channel", "a channel of the rig");
  channel_index(f, name, channels);
  return name;
}

playback::RawKey key(const Fields& f, const json& v, const std::string& channel, const std::string& field) {
  if (!v.is_object()) f.fail(field + ": expected a key ({\"time\": ..., \"value\": ..., ...}), found " + Fields::kind(v));
  try {
    return config::load_key_text(v.dump(), channel, f.what() + ", " + field);
  } catch (const InputError& e) {
    f.fail(field + ": " + e.problem());
  }
}

std::vector<std::size_t> indices(const Fields& f, const json& list) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < list.size(); ++i) out.push_back(f.index(list[i], "keys[" + std::to_string(i) + "]"));
  return out;
}

edit::KeyEdit key_edit(const json& v, std::size_t n, const std::vector<std::string>& channels) {
  const Fields f(v, "edit " + std::to_string(n + 1) + " of message 'edit'");
  const std::string op = f.text("op", "add, delete, move, set, insert_time, delete_time or markers");
  if (op == "add") {
    f.expect_only({"op", "channel", "keys"});
    const std::string c = channel(f, channels);
    const json& list = f.array("keys", "the keys to add");
    std::vector<playback::RawKey> keys;
    for (std::size_t i = 0; i < list.size(); ++i) keys.push_back(key(f, list[i], c, "keys[" + std::to_string(i) + "]"));
    return edit::AddKeys{c, std::move(keys)};
  }
  if (op == "delete") {
    f.expect_only({"op", "channel", "keys"});
    const std::string c = channel(f, channels);
    return edit::DeleteKeys{c, indices(f, f.array("keys", "the indices of the keys to delete"))};
  }
  if (op == "move") {
    f.expect_only({"op", "channel", "keys", "dt", "dv"});
    const std::string c = channel(f, channels);
    return edit::MoveKeys{c, indices(f, f.array("keys", "the indices of the keys to move")), f.number("dt", "seconds"),
                          f.number("dv", "channel units")};
  }
  if (op == "set") {
    f.expect_only({"op", "channel", "key", "value"});
    const std::string c = channel(f, channels);
    return edit::SetKey{c, f.index(f.at("key", "the index of the key"), "field 'key'"),
                        key(f, f.at("value", "the key"), c, "value")};
  }
  if (op == "insert_time") {
    f.expect_only({"op", "at", "length"});
    return edit::InsertTime{f.number("at", "show time in seconds"), f.number("length", "seconds to insert")};
  }
  if (op == "delete_time") {
    f.expect_only({"op", "from", "to"});
    return edit::DeleteTime{f.number("from", "show time in seconds"), f.number("to", "show time in seconds")};
  }
  if (op == "markers") {
    f.expect_only({"op", "markers"});
    const json& list = f.array("markers", "the show's markers, each {time, name}");
    edit::SetMarkers markers;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Fields m(list[i], "markers[" + std::to_string(i) + "] of edit " + std::to_string(n + 1));
      m.expect_only({"time", "name"});
      markers.markers.push_back({m.number("time", "show time in seconds"), m.text("name", "the marker's name"), {}});
    }
    return markers;
  }
  f.fail("unknown op \"" + op + "\"; expected add, delete, move, set, insert_time, delete_time or markers");
}

}  // namespace

ClientMessage parse_client_message(std::string_view text, const std::vector<std::string>& channels,
                                   const std::vector<std::string>& targets) {
  json message;
  try {
    message = json::parse(text);
  } catch (const json::exception& e) {  // a syntax error, or a number past a double
    throw ProtocolError(std::string("a message that is not JSON (or has a number past a double): ") + e.what());
  }
  const Fields top(message, "a message");
  const std::string type = top.text("type", "what the message asks");
  const Fields f(message, "message '" + type + "'");
  using session::Command;
  using session::CommandKind;
  const auto plain = [&](auto result) -> ClientMessage {
    f.expect_only({"type"});
    return result;
  };
  if (type == "play") return plain(Command{CommandKind::play, 0, 0});
  if (type == "pause") return plain(Command{CommandKind::pause, 0, 0});
  if (type == "stop") return plain(Command{CommandKind::stop, 0, 0});
  if (type == "estop") return plain(Estop{});
  if (type == "undo") return plain(Undo{});
  if (type == "redo") return plain(Redo{});
  if (type == "save") return plain(Save{});
  if (type == "curves") {
    f.expect_only({"type", "channels"});
    Curves c;
    if (message.contains("channels")) {
      c.channels.emplace();
      for (const json& name : f.array("channels", "the channels whose curves to send")) {
        if (!name.is_string()) f.fail("field 'channels': expected channel names, found " + Fields::kind(name));
        channel_index(f, name.get<std::string>(), channels);
        c.channels->push_back(name.get<std::string>());
      }
    }
    return c;
  }
  if (type == "check") return plain(Check{});
  if (type == "retime") return plain(Retime{});
  if (type == "waveform") return plain(Waveform{});
  if (type == "seek" || type == "scrub") {
    f.expect_only({"type", "time"});
    return Command{type == "seek" ? CommandKind::seek : CommandKind::scrub, 0, f.number("time", "show time in seconds")};
  }
  if (type == "loop") {
    f.expect_only({"type", "on"});
    return Command{CommandKind::loop, 0, f.boolean("on", "whether the show loops") ? 1.0 : 0.0};
  }
  if (type == "hold" || type == "release") {
    if (type == "hold") f.expect_only({"type", "channel", "value"});
    else f.expect_only({"type", "channel"});
    const auto c = static_cast<std::uint32_t>(channel_index(f, f.text("channel", "a channel of the rig"), channels));
    if (type == "release") return Command{CommandKind::release, c, 0};
    return Command{CommandKind::hold, c, f.number("value", "the channel's value in its units")};
  }
  if (type == "aim" || type == "release_aim") {
    if (type == "aim") f.expect_only({"type", "target", "point"});
    else f.expect_only({"type", "target"});
    Command c{type == "aim" ? CommandKind::aim : CommandKind::unaim,
              target_index(f, f.text("target", "a target of the show, by its effector's name"), targets),
              0,
              {}};
    if (type == "aim") c.point = point(f);
    return c;
  }
  if (type == "edit") {
    f.expect_only({"type", "edits", "continues"});
    const json& list = f.array("edits", "the edits, applied as one undo step");
    if (list.empty()) f.fail("field 'edits': expected at least one edit");
    Edit e;
    for (std::size_t i = 0; i < list.size(); ++i) e.edits.push_back(key_edit(list[i], i, channels));
    if (message.contains("continues")) e.continues = f.boolean("continues", "whether this continues the last edit (a drag)");
    return e;
  }
  f.fail("unknown type \"" + type +
         "\"; expected one of: play, pause, seek, scrub, loop, hold, release, aim, release_aim, stop, estop, edit, undo, redo, "
         "save, "
         "retime, curves, check, waveform");
}

}  // namespace avar::studio
