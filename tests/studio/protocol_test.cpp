// The studio's protocol: every message type parsed into what the server does, channels resolved
// against the rig, key edits with keys checked by the show reader's rules, every malformed message
// refused with the message, the field and what was expected; and the show's JSON, whose keys read
// back through the same key reader to the same bits.
#include "avar/studio/protocol.hpp"

#include <gtest/gtest.h>

#include <array>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"

namespace avar::studio {
namespace {

using session::Command;
using session::CommandKind;

const std::vector<std::string> kChannels = {"neck_pan", "neck_tilt", "jaw"};

Command command(const std::string& text) {
  const ClientMessage m = parse_client_message(text, kChannels);
  EXPECT_TRUE(std::holds_alternative<Command>(m)) << text;
  return std::get<Command>(m);
}

std::string refusal(const std::string& text) {
  try {
    parse_client_message(text, kChannels);
  } catch (const ProtocolError& e) {
    return e.what();
  }
  ADD_FAILURE() << "taken: " << text;
  return "";
}

TEST(StudioProtocol, TransportMessagesBecomeSessionCommands) {
  EXPECT_EQ(command(R"({"type": "play"})").kind, CommandKind::play);
  EXPECT_EQ(command(R"({"type": "pause"})").kind, CommandKind::pause);
  EXPECT_EQ(command(R"({"type": "stop"})").kind, CommandKind::stop);
  const Command seek = command(R"({"type": "seek", "time": 2.5})");
  EXPECT_EQ(seek.kind, CommandKind::seek);
  EXPECT_EQ(seek.value, 2.5);
  const Command scrub = command(R"({"type": "scrub", "time": 0.1})");
  EXPECT_EQ(scrub.kind, CommandKind::scrub);
  EXPECT_EQ(scrub.value, 0.1);
  EXPECT_EQ(command(R"({"type": "loop", "on": true})").value, 1.0);
  EXPECT_EQ(command(R"({"type": "loop", "on": false})").value, 0.0);
  const Command hold = command(R"({"type": "hold", "channel": "jaw", "value": -12.25})");
  EXPECT_EQ(hold.kind, CommandKind::hold);
  EXPECT_EQ(hold.channel, 2u);
  EXPECT_EQ(hold.value, -12.25);
  const Command release = command(R"({"type": "release", "channel": "neck_tilt"})");
  EXPECT_EQ(release.kind, CommandKind::release);
  EXPECT_EQ(release.channel, 1u);
  EXPECT_TRUE(std::holds_alternative<Estop>(parse_client_message(R"({"type": "estop"})", kChannels)));
  EXPECT_TRUE(std::holds_alternative<Undo>(parse_client_message(R"({"type": "undo"})", kChannels)));
  EXPECT_TRUE(std::holds_alternative<Redo>(parse_client_message(R"({"type": "redo"})", kChannels)));
  EXPECT_TRUE(std::holds_alternative<Save>(parse_client_message(R"({"type": "save"})", kChannels)));
}

TEST(StudioProtocol, AimHoldsATargetOfTheShowByItsEffectorsName) {
  const std::vector<std::string> targets = {"eyes", "hand"};
  const auto parse = [&](const std::string& text) { return std::get<Command>(parse_client_message(text, kChannels, targets)); };
  const Command aim = parse(R"({"type": "aim", "target": "hand", "point": [0.5, -0.25, 1]})");
  EXPECT_EQ(aim.kind, CommandKind::aim);
  EXPECT_EQ(aim.channel, 1u);
  EXPECT_EQ(aim.point, (std::array<double, 3>{0.5, -0.25, 1}));
  const Command release = parse(R"({"type": "release_aim", "target": "eyes"})");
  EXPECT_EQ(release.kind, CommandKind::unaim);
  EXPECT_EQ(release.channel, 0u);
  const auto refused = [&](const std::string& text) {
    try {
      parse_client_message(text, kChannels, targets);
    } catch (const ProtocolError& e) {
      return std::string(e.what());
    }
    return std::string("taken");
  };
  EXPECT_EQ(refused(R"({"type": "aim", "target": "tail", "point": [0, 0, 0]})"),
            "message 'aim': no target 'tail' in the show; expected one of: eyes, hand");
  EXPECT_EQ(refused(R"({"type": "aim", "target": "eyes", "point": [0, 0]})"),
            "message 'aim': field 'point': expected [x, y, z] in metres, three numbers; found 2");
  EXPECT_EQ(refused(R"({"type": "aim", "target": "eyes", "point": [0, "1", 0]})"),
            "message 'aim': field 'point': expected [x, y, z] in metres, finite numbers; found the string \"1\"");
  EXPECT_EQ(refusal(R"({"type": "aim", "target": "eyes", "point": [0, 0, 0]})"),
            "message 'aim': field 'target': the show has no targets to aim ('eyes' asked)");
}

TEST(StudioProtocol, AnEditMessageIsAGroupOfKeyEdits) {
  const ClientMessage m = parse_client_message(R"({"type": "edit", "edits": [
      {"op": "add", "channel": "jaw", "keys": [{"time": 1.5, "value": 10, "interpolation": "bezier", "right": [1.7, 12],
                                               "right_type": "free", "left_type": "auto"}]},
      {"op": "delete", "channel": "jaw", "keys": [0, 3]},
      {"op": "move", "channel": "neck_pan", "keys": [2], "dt": -0.25, "dv": 4},
      {"op": "set", "channel": "neck_tilt", "key": 1, "value": {"time": 2, "value": 5, "interpolation": "elastic",
                                                              "easing": "ease_out", "amplitude": 3, "period": 0.2}}]})",
                                               kChannels);
  ASSERT_TRUE(std::holds_alternative<Edit>(m));
  const std::vector<edit::KeyEdit>& edits = std::get<Edit>(m).edits;
  ASSERT_EQ(edits.size(), 4u);
  const auto& add = std::get<edit::AddKeys>(edits[0]);
  EXPECT_EQ(add.channel, "jaw");
  ASSERT_EQ(add.keys.size(), 1u);
  EXPECT_EQ(add.keys[0].time, 1.5);
  EXPECT_EQ(add.keys[0].interpolation, playback::Interpolation::bezier);
  ASSERT_TRUE(add.keys[0].right);
  EXPECT_EQ(add.keys[0].right->time, 1.7);
  EXPECT_EQ(add.keys[0].right->value, 12);
  EXPECT_EQ(add.keys[0].right_type, playback::HandleType::free);
  EXPECT_EQ(add.keys[0].left_type, playback::HandleType::automatic);
  EXPECT_EQ(std::get<edit::DeleteKeys>(edits[1]).keys, (std::vector<std::size_t>{0, 3}));
  const auto& move = std::get<edit::MoveKeys>(edits[2]);
  EXPECT_EQ(move.channel, "neck_pan");
  EXPECT_EQ(move.dt, -0.25);
  EXPECT_EQ(move.dv, 4);
  const ClientMessage ripple = parse_client_message(
      R"({"type": "edit", "edits": [{"op": "insert_time", "at": 2, "length": 0.5}, {"op": "delete_time", "from": 4, "to": 4.25}]})",
      kChannels);
  EXPECT_FALSE(std::get<Edit>(ripple).continues);
  const ClientMessage drag = parse_client_message(
      R"({"type": "edit", "continues": true, "edits": [{"op": "move", "channel": "jaw", "keys": [1], "dt": 0, "dv": 0.5}]})",
      kChannels);
  EXPECT_TRUE(std::get<Edit>(drag).continues);
  const std::vector<edit::KeyEdit>& time_edits = std::get<Edit>(ripple).edits;
  ASSERT_EQ(time_edits.size(), 2u);
  EXPECT_EQ(std::get<edit::InsertTime>(time_edits[0]).length, 0.5);
  EXPECT_EQ(std::get<edit::DeleteTime>(time_edits[1]).to, 4.25);
  const auto& set = std::get<edit::SetKey>(edits[3]);
  EXPECT_EQ(set.key, 1u);
  EXPECT_EQ(set.value.interpolation, playback::Interpolation::elastic);
  EXPECT_EQ(set.value.easing, playback::Easing::ease_out);
  EXPECT_EQ(set.value.amplitude, 3);
  EXPECT_EQ(set.value.period, 0.2);
  const ClientMessage markers = parse_client_message(
      R"({"type": "edit", "edits": [{"op": "markers", "markers": [{"time": 2.5, "name": "scream"}, {"time": 1, "name": "in"}]}]})",
      kChannels);
  const auto& set_markers = std::get<edit::SetMarkers>(std::get<Edit>(markers).edits[0]);
  ASSERT_EQ(set_markers.markers.size(), 2u);
  EXPECT_EQ(set_markers.markers[0].time, 2.5);
  EXPECT_EQ(set_markers.markers[0].name, "scream");
  EXPECT_EQ(set_markers.markers[1].name, "in");
}

TEST(StudioProtocol, AMalformedMessageIsRefusedNamingTheFieldAndWhatWasExpected) {
  EXPECT_NE(refusal("{type: play}").find("a message that is not JSON"), std::string::npos);
  EXPECT_EQ(refusal("[1, 2]"), "a message: expected a JSON object, found a list");
  EXPECT_EQ(refusal(R"({"time": 1})"), "a message: missing field 'type' (what the message asks)");
  EXPECT_EQ(refusal(R"({"type": "jump"})"),
            "message 'jump': unknown type \"jump\"; expected one of: play, pause, seek, scrub, loop, hold, release, aim, "
            "release_aim, stop, estop, edit, undo, redo, save, retime, curves, check, waveform");
  EXPECT_EQ(refusal(R"({"type": "seek"})"), "message 'seek': missing field 'time' (show time in seconds)");
  EXPECT_EQ(refusal(R"({"type": "seek", "time": "1"})"),
            "message 'seek': field 'time': expected show time in seconds, a finite number; found the string \"1\"");
  EXPECT_NE(refusal(R"({"type": "seek", "time": 1e999})").find("number overflow"), std::string::npos);
  EXPECT_EQ(refusal(R"({"type": "play", "now": true})"), "message 'play': unknown field 'now'; expected only: type");
  EXPECT_EQ(refusal(R"({"type": "hold", "channel": "jawz", "value": 1})"),
            "message 'hold': no channel 'jawz' in the rig; expected one of: neck_pan, neck_tilt, jaw");
  EXPECT_EQ(refusal(R"({"type": "loop", "on": 1})"),
            "message 'loop': field 'on': expected whether the show loops, true or false; found the number 1");
  EXPECT_EQ(refusal(R"({"type": "edit", "edits": []})"), "message 'edit': field 'edits': expected at least one edit");
  EXPECT_EQ(refusal(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [-1], "dt": 0, "dv": 0}]})"),
            "edit 1 of message 'edit': keys[0]: expected a key index (0, 1, ...), found the number -1");
  EXPECT_EQ(
      refusal(R"({"type": "edit", "edits": [{"op": "shift", "channel": "jaw"}]})"),
      "edit 1 of message 'edit': unknown op \"shift\"; expected add, delete, move, set, insert_time, delete_time or markers");
  // The key's own fields: the show reader's words.
  const std::string easing_on_linear = refusal(
      R"({"type": "edit", "edits": [{"op": "add", "channel": "jaw", "keys": [{"time": 1, "value": 2, "easing": "ease_in"}]}]})");
  EXPECT_NE(easing_on_linear.find(
                "edit 1 of message 'edit': keys[0]: field 'easing' does not belong to a key with linear interpolation"),
            std::string::npos)
      << easing_on_linear;
  const std::string no_value = refusal(R"({"type": "edit", "edits": [{"op": "add", "channel": "jaw", "keys": [{"time": 1}]}]})");
  EXPECT_NE(no_value.find("keys[0]: missing field 'value'"), std::string::npos) << no_value;
}

TEST(StudioProtocol, TheShowsJsonKeysReadBackThroughTheKeyReaderToTheSameBits) {
  for (const char* name : {"hello-head", "curves-tour", "stage-lights"}) {
    const playback::Show show = config::load_show_file(std::string(AVAR_SOURCE_DIR "/examples/shows/") + name + ".yaml");
    const nlohmann::json j = nlohmann::json::parse(config::show_json(show));
    EXPECT_EQ(j["name"], show.name);
    EXPECT_EQ(j["duration"].get<double>(), show.duration);
    for (const playback::Track& track : show.tracks) {
      const nlohmann::json& curve = j["tracks"][track.channel];
      const nlohmann::json& keys = curve.is_object() ? curve["keys"] : curve;
      ASSERT_EQ(keys.size(), track.raw.keys.size()) << name << " " << track.channel;
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const playback::RawKey k = config::load_key_text(keys[i].dump(), track.channel, "show json");
        EXPECT_EQ(k.time, track.raw.keys[i].time) << name << " " << track.channel << " key " << i;
        EXPECT_EQ(k.value, track.raw.keys[i].value) << name << " " << track.channel << " key " << i;
        EXPECT_EQ(k.interpolation, track.raw.keys[i].interpolation) << name << " " << track.channel << " key " << i;
        EXPECT_EQ(k.right.has_value(), track.raw.keys[i].right.has_value());
        if (k.right) {
          EXPECT_EQ(k.right->value, track.raw.keys[i].right->value);
        }
      }
    }
  }
}

}  // namespace
}  // namespace avar::studio
