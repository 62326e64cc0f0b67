// The studio apart from its transport: what a client is told when it connects, edits that reach
// the running figure at the next tick, undo and redo, save (the original bytes when the show is
// as opened), refusals that name what was wrong, and the status made from the tick records.
#include "avar/studio/studio.hpp"
#include "avar/studio/studio_run.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"
#include "avar/playback/runtime/raw_curve_codec.hpp"
#include "support/temp_file.hpp"
#include "support/wav_file.hpp"

namespace avar::studio {
namespace {

using nlohmann::json;

std::string example(const std::string& path) { return std::string(AVAR_SOURCE_DIR) + "/examples/" + path; }

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Calls `act` with every record, on the stepped loop's thread between ticks.
class EachTick final : public session::SessionObserver {
 public:
  explicit EachTick(std::function<void(const session::TickRecord&)> act) : act_(std::move(act)) {}
  void on_tick(const session::TickRecord& r) override { act_(r); }

 private:
  std::function<void(const session::TickRecord&)> act_;
};

/// The hello-head figure in a studio: the show copied to a file of the test's own, a stepped
/// session on simulated links playing the studio's copy.
struct StudioFigure {
  rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  std::string original = read_all(example("shows/hello-head.yaml"));
  std::string path = testing::write_temp_file("show.yaml", original);
  Studio studio{rig, edit::ShowDocument::open(path), path};
  session::ShowSession session{rig, studio.initial_show(), config()};
  std::atomic<int> interrupts{0};

  static session::SessionConfig config() {
    session::SessionConfig c;
    c.stepped = true;
    c.links.simulate_all = true;
    c.hold_at_end = true;
    c.start_paused = true;
    return c;
  }
  StudioFigure() { studio.attach(&session); }
  ~StudioFigure() { studio.attach(nullptr); }
  std::size_t channel(const std::string& name) const { return *rig.find_channel(name); }
  /// Runs the session with `act` called every tick; `act` returns false to stop the run.
  void run(const std::function<bool(const session::TickRecord&)>& act) {
    bool stopped = false;
    EachTick each([&](const session::TickRecord& r) {
      if (!stopped && !act(r)) {
        stopped = true;
        session.stop();
      }
    });
    session.add_observer(studio);
    session.add_observer(each);
    ASSERT_FALSE(session.start_links());
    session.begin();
    (void)session.run(interrupts);
  }
};

json reply(const Replies& r) { return json::parse(r.to_sender); }

TEST(Studio, HelloTellsTheRigAndTheShow) {
  StudioFigure f;
  const json hello = json::parse(f.studio.hello());
  EXPECT_EQ(hello["type"], "hello");
  EXPECT_EQ(hello["protocol"], 1);
  EXPECT_EQ(hello["rig"]["name"], "hello-head");
  ASSERT_EQ(hello["rig"]["channels"].size(), f.rig.channels.size());
  const json& jaw = hello["rig"]["channels"][f.channel("jaw")];
  EXPECT_EQ(jaw["name"], "jaw");
  EXPECT_EQ(jaw["min"].get<double>(), f.rig.channels[f.channel("jaw")].min);
  EXPECT_EQ(jaw["max_velocity"].get<double>(), f.rig.channels[f.channel("jaw")].max_velocity);
  EXPECT_EQ(hello["show"]["name"], "hello-head");
  EXPECT_EQ(hello["version"], 0);
  EXPECT_EQ(hello["file"], f.path);
  EXPECT_EQ(hello["modified"], false);
  EXPECT_EQ(hello["undo"], "");
  EXPECT_TRUE(hello["rig"]["kinematics"].is_null()) << "hello-head has no kinematics section";
  // The editor's menus: the show file's names, in its order.
  EXPECT_EQ(hello["vocabulary"]["interpolations"].size(), 18u);
  EXPECT_EQ(hello["vocabulary"]["interpolations"][2], "bezier");
  EXPECT_EQ(hello["vocabulary"]["easings"], json({"auto", "ease_in", "ease_out", "ease_in_out"}));
  EXPECT_EQ(hello["vocabulary"]["handle_types"], json({"free", "aligned", "vector", "auto", "auto_clamped"}));
  EXPECT_EQ(hello["vocabulary"]["extrapolations"], json({"constant", "linear"}));
}

TEST(Studio, HelloGivesTheKinematicTreeWithTheChannelDrivingEachJoint) {
  const rig::Rig rig = config::load_rig_file(example("rigs/gaze-head.yaml"));
  Studio studio{rig, edit::ShowDocument(new_show("look")), ""};
  const json k = json::parse(studio.hello())["rig"]["kinematics"];
  ASSERT_EQ(k["joints"].size(), 2u);
  const json& pan = k["joints"][0];
  EXPECT_EQ(pan["name"], "pan");
  EXPECT_EQ(pan["type"], "revolute");
  EXPECT_TRUE(pan["parent"].is_null());
  EXPECT_EQ(pan["channel"], "neck_pan");
  EXPECT_EQ(pan["axis"], json({0.0, 0.0, 1.0}));
  EXPECT_EQ(pan["origin"]["xyz"], json({0.0, 0.0, 0.30}));
  EXPECT_EQ(pan["origin"]["quaternion"], json({1.0, 0.0, 0.0, 0.0}));
  // Degrees on the channel, radians at the joint.
  EXPECT_NEAR(pan["scale"].get<double>(), M_PI / 180, 1e-15);
  const json& tilt = k["joints"][1];
  EXPECT_EQ(tilt["parent"], 0);
  EXPECT_EQ(tilt["channel"], "neck_tilt");
  ASSERT_EQ(k["effectors"].size(), 1u);
  EXPECT_EQ(k["effectors"][0]["name"], "eyes");
  EXPECT_EQ(k["effectors"][0]["joint"], 1);
  EXPECT_EQ(k["effectors"][0]["origin"]["xyz"], json({0.09, 0.0, 0.04}));
}

TEST(Studio, AnEditReachesTheFigureAtTheNextTickAndUndoTakesItBack) {
  StudioFigure f;
  const std::size_t jaw = f.channel("jaw");
  std::vector<double> targets;
  Replies edited, undone;
  f.run([&](const session::TickRecord& r) {
    targets.push_back(r.channels[jaw].target);
    if (r.tick == 5) (void)f.studio.handle(R"({"type": "scrub", "time": 6.8})");
    if (r.tick == 100)  // the jaw's key at 6.8 s, 18 -> 8
      edited =
          f.studio.handle(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0, "dv": -10}]})");
    if (r.tick == 200) undone = f.studio.handle(R"({"type": "undo"})");
    return r.tick < 300;
  });
  EXPECT_EQ(reply(edited)["type"], "ok");
  ASSERT_EQ(edited.to_all.size(), 1u);
  // Every client is told the keys that changed (and the one after them), not the whole show.
  const json keys = json::parse(edited.to_all[0]);
  EXPECT_EQ(keys["type"], "keys");
  EXPECT_EQ(keys["version"], 1);
  EXPECT_EQ(keys["modified"], true);
  EXPECT_EQ(keys["undo"], "move 1 key of 'jaw' by 0 s, -10");
  ASSERT_EQ(keys["tracks"].size(), 1u);
  EXPECT_EQ(keys["tracks"][0]["channel"], "jaw");
  EXPECT_EQ(keys["tracks"][0]["from"], 2);
  EXPECT_EQ(keys["tracks"][0]["remove"], 2);
  ASSERT_EQ(keys["tracks"][0]["keys"].size(), 2u);
  EXPECT_EQ(keys["tracks"][0]["keys"][0]["value"].get<double>(), 8.0);
  EXPECT_EQ(json::parse(undone.to_all.at(0))["type"], "keys");
  EXPECT_EQ(json::parse(undone.to_all.at(0))["version"], 2);
  EXPECT_EQ(json::parse(undone.to_all.at(0))["modified"], false);
  ASSERT_GT(targets.size(), 300u);
  EXPECT_DOUBLE_EQ(targets[100], 18.0);
  EXPECT_DOUBLE_EQ(targets[101], 8.0);
  EXPECT_DOUBLE_EQ(targets[201], 18.0);
}

TEST(Studio, TheChangedKeysAreWrittenAsTheShowWritesThemAndATimeEditSendsTheWholeShow) {
  StudioFigure f;
  const Replies moved = f.studio.handle(
      R"({"type": "edit", "edits": [{"op": "move", "channel": "neck_pan", "keys": [1, 2], "dt": 0.01, "dv": 3}]})");
  ASSERT_EQ(reply(moved)["type"], "ok");
  const json keys = json::parse(moved.to_all.at(0));
  ASSERT_EQ(keys["type"], "keys");
  const json show = json::parse(config::show_json(f.studio.document().show()));
  const json& track = keys["tracks"].at(0);
  EXPECT_EQ(track["channel"], "neck_pan");
  EXPECT_EQ(track["from"], 1);
  for (std::size_t i = 0; i < track["keys"].size(); ++i)
    EXPECT_EQ(track["keys"][i], show["tracks"]["neck_pan"][1 + i]) << "key " << 1 + i;
  // A ripple moves every track and the cues: only the whole show tells.
  const Replies rippled = f.studio.handle(R"({"type": "edit", "edits": [{"op": "insert_time", "at": 1, "length": 0.5}]})");
  ASSERT_EQ(reply(rippled)["type"], "ok");
  const json whole = json::parse(rippled.to_all.at(0));
  EXPECT_EQ(whole["type"], "show");
  EXPECT_EQ(whole["show"], json::parse(config::show_json(f.studio.document().show())));
}

TEST(Studio, TheWaveformIsTheSoundATrackWasMadeFromAsPeaks) {
  // One second of a 100 Hz tone at half scale, the jaw following it from 0.5 s.
  std::vector<float> tone(8000);
  for (std::size_t i = 0; i < tone.size(); ++i)
    tone[i] = 0.5f * static_cast<float>(std::sin(2 * M_PI * 100.0 * static_cast<double>(i) / 8000.0));
  const std::string show = testing::write_temp_file("voice.yaml", R"(name: voice
duration: 2
tracks:
  jaw:
    audio: {file: voice.wav, start: 0.5, open: 20}
)");
  testing::write_wav_mono16((std::filesystem::path(show).parent_path() / "voice.wav").string(), tone, 8000);
  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  Studio studio(rig, edit::ShowDocument::open(show), show);
  const json wave = reply(studio.handle(R"({"type": "waveform"})"));
  ASSERT_EQ(wave["type"], "waveform");
  ASSERT_EQ(wave["tracks"].size(), 1u);
  const json& jaw = wave["tracks"][0];
  EXPECT_EQ(jaw["channel"], "jaw");
  EXPECT_EQ(jaw["start"], 0.5);
  EXPECT_EQ(jaw["duration"], 1.0);
  EXPECT_EQ(jaw["bucket"], 0.01);
  const auto peaks = jaw["peaks"].get<std::vector<double>>();
  ASSERT_EQ(peaks.size(), 200u);  // a low and a high per 10 ms
  for (std::size_t b = 0; b < 100; ++b) {
    // Every 10 ms holds a whole period of the tone: its trough and its crest, to 16-bit rounding.
    EXPECT_NEAR(peaks[2 * b], -0.5, 2e-3) << "bucket " << b;
    EXPECT_NEAR(peaks[2 * b + 1], 0.5, 2e-3) << "bucket " << b;
  }
  // Time inserted before the sound moves it with the jaw's keys; undo moves it back.
  ASSERT_EQ(reply(studio.handle(R"({"type": "edit", "edits": [{"op": "insert_time", "at": 0.2, "length": 0.25}]})"))["type"],
            "ok");
  EXPECT_EQ(reply(studio.handle(R"({"type": "waveform"})"))["tracks"][0]["start"], 0.75);
  ASSERT_EQ(reply(studio.handle(R"({"type": "edit", "edits": [{"op": "delete_time", "from": 0.5, "to": 1}]})"))["type"], "ok");
  EXPECT_EQ(reply(studio.handle(R"({"type": "waveform"})"))["tracks"][0]["start"], 0.5);  // cut out: where the cut was
  ASSERT_EQ(reply(studio.handle(R"({"type": "undo"})"))["type"], "ok");
  ASSERT_EQ(reply(studio.handle(R"({"type": "undo"})"))["type"], "ok");
  EXPECT_EQ(reply(studio.handle(R"({"type": "waveform"})"))["tracks"][0]["start"], 0.5);
  // The sound gone since the show was read: the reply names the file.
  std::filesystem::remove(std::filesystem::path(show).parent_path() / "voice.wav");
  const json gone = reply(studio.handle(R"({"type": "waveform"})"));
  EXPECT_EQ(gone["type"], "error");
  EXPECT_NE(gone["message"].get<std::string>().find("voice.wav"), std::string::npos) << gone["message"];
}

TEST(Studio, SavesTheOriginalBytesWhenTheShowIsAsOpenedAndTheEditOtherwise) {
  StudioFigure f;
  const Replies moved =
      f.studio.handle(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0.05, "dv": 0}]})");
  ASSERT_EQ(reply(moved)["type"], "ok");
  const Replies saved = f.studio.handle(R"({"type": "save"})");
  EXPECT_EQ(reply(saved)["type"], "saved");
  EXPECT_EQ(reply(saved)["file"], f.path);
  const std::string edited = read_all(f.path);
  EXPECT_NE(edited, f.original);
  const json reread = json::parse(config::show_json(config::load_show_file(f.path)));
  EXPECT_NEAR(reread["tracks"]["jaw"][2]["time"].get<double>(), 6.85, 1e-12);
  ASSERT_EQ(reply(f.studio.handle(R"({"type": "undo"})"))["type"], "ok");
  ASSERT_EQ(reply(f.studio.handle(R"({"type": "save"})"))["type"], "saved");
  EXPECT_EQ(read_all(f.path), f.original);
}

TEST(Studio, RefusalsNameWhatWasWrongAndChangeNothing) {
  StudioFigure f;
  const json nothing = reply(f.studio.handle(R"({"type": "undo"})"));
  EXPECT_EQ(nothing["type"], "error");
  EXPECT_EQ(nothing["request"], "undo");
  EXPECT_EQ(nothing["message"], "message 'undo': there is nothing to undo");
  const json clash =
      reply(f.studio.handle(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0.2, "dv": 0}]})"));
  EXPECT_EQ(clash["type"], "error");
  EXPECT_NE(clash["message"].get<std::string>().find("jaw"), std::string::npos) << clash["message"];
  const json unknown = reply(f.studio.handle(R"({"type": "hold", "channel": "tail", "value": 1})"));
  EXPECT_EQ(unknown["type"], "error");
  EXPECT_NE(unknown["message"].get<std::string>().find("tail"), std::string::npos);
  const json garbage = reply(f.studio.handle("not json"));
  EXPECT_EQ(garbage["type"], "error");
  EXPECT_FALSE(f.studio.document().modified());
  EXPECT_EQ(json::parse(f.studio.hello())["version"], 0);
}

TEST(Studio, ASliderHoldsItsChannelAndTheStatusSaysWhereTheFigureIs) {
  StudioFigure f;
  const std::size_t jaw = f.channel("jaw");
  std::vector<std::string> statuses;
  f.run([&](const session::TickRecord& r) {
    if (r.tick == 5) {
      EXPECT_EQ(reply(f.studio.handle(R"({"type": "hold", "channel": "jaw", "value": 15})"))["type"], "ok");
      EXPECT_EQ(reply(f.studio.handle(R"({"type": "loop", "on": true})"))["type"], "ok");
    }
    if (r.tick % 10 == 0)
      for (std::string& s : f.studio.take_status()) statuses.push_back(std::move(s));
    return r.tick < 300;
  });
  ASSERT_FALSE(statuses.empty());
  const json last = json::parse(statuses.back());
  EXPECT_EQ(last["type"], "status");
  EXPECT_EQ(last["phase"], "running");
  EXPECT_EQ(last["paused"], true);
  EXPECT_EQ(last["loop"], true);  // hello-head does not loop; a client asked
  EXPECT_EQ(json::parse(statuses.front())["loop"], false);
  EXPECT_EQ(last["show_time"].get<double>(), 0.0);
  EXPECT_EQ(last["fault"], nullptr);
  const json& ch = last["channels"][jaw];
  EXPECT_EQ(ch["name"], "jaw");
  EXPECT_EQ(ch["held"], true);
  EXPECT_NEAR(ch["command"].get<double>(), 15.0, 1e-9);
  EXPECT_NEAR(ch["measured"].get<double>(), 15.0, 0.5);  // the simulated servo is getting there
  ASSERT_EQ(last["links"].size(), f.rig.links.size());
  EXPECT_EQ(last["links"][0]["name"], f.rig.links[0].name);
}

TEST(Studio, CurvesAreTheTracksAsTheEnginesFlatKeysAndFollowEdits) {
  StudioFigure f;
  ASSERT_EQ(reply(f.studio.handle(
                R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0, "dv": -10}]})"))["type"],
            "ok");
  const json curves = reply(f.studio.handle(R"({"type": "curves"})"));
  EXPECT_EQ(curves["type"], "curves");
  EXPECT_EQ(curves["version"], 1);
  EXPECT_EQ(curves["format"], playback::kRawCurveFormat);
  const playback::Show& show = f.studio.document().show();
  ASSERT_EQ(curves["tracks"].size(), show.tracks.size());
  for (const playback::Track& track : show.tracks) {
    // Built from the numbers as sent (JSON doubles read back exactly), the curve samples as the
    // show's own, edit included.
    const auto flat = curves["tracks"][track.channel].get<std::vector<double>>();
    const playback::Curve rebuilt = playback::Curve::build(playback::decode_raw_curve(flat));
    for (int i = -10; i <= 1300; ++i) ASSERT_EQ(rebuilt.evaluate(i * 0.01), track.curve.evaluate(i * 0.01)) << track.channel;
  }
  // A client that was told which tracks changed asks for those alone.
  const json jaw = reply(f.studio.handle(R"({"type": "curves", "channels": ["jaw"]})"));
  ASSERT_EQ(jaw["tracks"].size(), 1u);
  EXPECT_EQ(jaw["tracks"]["jaw"], curves["tracks"]["jaw"]);
  EXPECT_EQ(reply(f.studio.handle(R"({"type": "curves", "channels": ["tail"]})"))["message"],
            "message 'curves': no channel 'tail' in the rig; expected one of: jaw, neck_pan, neck_tilt, neck_roll, eyes_pan, "
            "eyes_tilt, lid_left, lid_right");
}

TEST(Studio, CheckFindsWhatAsksTooMuchAndRetimeStretchesItAsOneStep) {
  StudioFigure f;
  const auto speed_findings = [&] {
    const json check = reply(f.studio.handle(R"({"type": "check"})"));
    EXPECT_EQ(check["type"], "check");
    std::vector<json> speed;
    for (const json& finding : check["findings"])
      if (finding["kind"] == "speed") speed.push_back(finding);
    return speed;
  };
  EXPECT_TRUE(speed_findings().empty());
  EXPECT_EQ(reply(f.studio.handle(R"({"type": "retime"})"))["type"], "error");
  // The jaw's 25 deg key moved to 0.05 s after its 2 deg key: 460 deg/s, allowed 300.
  ASSERT_EQ(reply(f.studio.handle(
                R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [8], "dt": -0.15, "dv": 0}]})"))["type"],
            "ok");
  const std::vector<json> found = speed_findings();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0]["channel"], "jaw");
  EXPECT_EQ(found[0]["unit"], "deg");
  EXPECT_NEAR(found[0]["t0"].get<double>(), 7.8, 1e-9);
  EXPECT_NEAR(found[0]["t1"].get<double>(), 7.85, 1e-9);
  EXPECT_NEAR(found[0]["required"].get<double>(), 460, 1e-6);
  EXPECT_EQ(found[0]["allowed"], 300);
  const Replies retimed = f.studio.handle(R"({"type": "retime"})");
  EXPECT_EQ(reply(retimed)["type"], "ok");
  ASSERT_EQ(retimed.to_all.size(), 1u);
  EXPECT_EQ(json::parse(retimed.to_all[0])["undo"].get<std::string>().rfind("retime 1 span", 0), 0u);
  EXPECT_TRUE(speed_findings().empty());
  EXPECT_EQ(reply(f.studio.handle(R"({"type": "undo"})"))["type"], "ok");
  EXPECT_EQ(speed_findings().size(), 1u);
}

TEST(Studio, CommandsWaitForAFigureButEditsDoNot) {
  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  Studio studio(rig, edit::ShowDocument(config::load_show_file(example("shows/hello-head.yaml"))), "");
  EXPECT_EQ(reply(studio.handle(R"({"type": "play"})"))["message"], "message 'play': no figure is running");
  EXPECT_EQ(reply(studio.handle(R"({"type": "edit", "edits": [{"op": "delete", "channel": "jaw", "keys": [0]}]})"))["type"],
            "ok");
  EXPECT_EQ(reply(studio.handle(R"({"type": "save"})"))["message"],
            "message 'save': the show has no file; start the studio with a show path to save to");
}

}  // namespace
}  // namespace avar::studio
