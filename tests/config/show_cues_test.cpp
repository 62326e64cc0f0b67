// The `cues:` of a show file: OSC and digital cues read in time order, digital ones turned into
// step tracks of their channels, and every bad cue named with file:line:col.

#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/config/show_writer.hpp"

namespace avar::config {
namespace {

const char* kCueShow = R"(name: cued
duration: 4
tracks:
  dim: [{time: 0, value: 0}, {time: 4, value: 50}]
cues:
  - {time: 3, osc: {to: 127.0.0.1:9000, address: /scene, args: [2, 0.5, go]}}
  - {time: 1, digital: {channel: strobe, value: 1}}
  - {time: 1.5, digital: {channel: strobe, value: 0}}
)";

std::string cue_show_error(const std::string& from, const std::string& to) {
  return avar::testing::load_error(load_show_file, avar::testing::replace(kCueShow, from, to), "cue_show.yaml");
}

TEST(ShowCues, ReadsOscAndDigitalCuesInTimeOrder) {
  const playback::Show show = load_show_file(testing::write_temp_file("cue_show.yaml", kCueShow));
  ASSERT_EQ(show.cues.size(), 3U);
  EXPECT_EQ(show.cues[0].time, 1.0);
  EXPECT_EQ(show.cues[0].digital_channel, "strobe");
  const playback::Cue& osc = show.cues[2];
  ASSERT_TRUE(osc.is_osc());
  EXPECT_EQ(osc.osc_host, "127.0.0.1");
  EXPECT_EQ(osc.osc_port, 9000);
  EXPECT_EQ(osc.osc_address, "/scene");
  ASSERT_EQ(osc.osc_arguments.size(), 3U);
  EXPECT_EQ(osc.osc_arguments[0].type, 'i');
  EXPECT_EQ(osc.osc_arguments[1].type, 'f');
  EXPECT_EQ(osc.osc_arguments[1].number, 0.5);
  EXPECT_EQ(osc.osc_arguments[2].type, 's');
  EXPECT_EQ(osc.osc_arguments[2].text, "go");
  // The digital cues are a step track: off, on at 1 s, off at 1.5 s.
  ASSERT_EQ(show.tracks.size(), 2U);
  const playback::Track& strobe = show.tracks[1];
  EXPECT_EQ(strobe.channel, "strobe");
  EXPECT_EQ(strobe.curve.evaluate(0.5), 0.0);
  EXPECT_EQ(strobe.curve.evaluate(1.0), 1.0);
  EXPECT_EQ(strobe.curve.evaluate(1.49), 1.0);
  EXPECT_EQ(strobe.curve.evaluate(1.5), 0.0);
  EXPECT_EQ(strobe.curve.evaluate(4.0), 0.0);
}

TEST(ShowCues, NamesEveryBadCueWhereItStands) {
  EXPECT_EQ(cue_show_error("{time: 3, osc", "{time: 5, osc"), ":6:12: cue 1 at 5 s never fires: the show runs from 0 to 4 s");
  EXPECT_EQ(cue_show_error("value: 1}}", "value: 2}}"), ":7:49: expected the value of cue 2 to be 0 (off) or 1 (on), found '2'");
  EXPECT_EQ(cue_show_error("address: /scene", "address: scene"),
            ":6:50: expected an OSC address such as /lights/go (starting with /, no spaces or # * , ? [ ] { }), found 'scene'");
  EXPECT_EQ(cue_show_error("to: 127.0.0.1:9000", "to: 127.0.0.1"),
            ":6:25: expected HOST:PORT for the OSC destination, found '127.0.0.1'");
  EXPECT_EQ(cue_show_error("to: 127.0.0.1:9000", "to: desk:9000"),
            ":6:25: expected the destination to be a numeric IPv4 address such as 10.0.0.20, found 'desk'");
  EXPECT_EQ(cue_show_error("{time: 1, digital", "{time: 1, osc: {to: 1.2.3.4:5, address: /a}, digital"),
            ":7:5: expected cue 2 to have exactly one of osc: {...} or digital: {...}");
  EXPECT_EQ(cue_show_error("{time: 1.5, digital", "{time: 1, digital"),
            ":8:5: channel 'strobe' has two digital cues at 1.000000 s; expected one cue per channel and time");
  EXPECT_EQ(cue_show_error("channel: strobe, value: 1", "channel: dim, value: 1"),
            ":6:3: channel 'dim' has a track and digital cues (the first at 7:5); expected one or the other");
}

TEST(ShowCues, ADigitalCueOnAnAnalogChannelFailsTheRigCheck) {
  const rig::Rig rig = load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/artnet-stage.yaml");
  const playback::Show show = load_show_file(testing::write_temp_file(
      "cue_show.yaml", avar::testing::replace(avar::testing::replace(kCueShow, "strobe", "key"), "strobe", "key")));
  const ShowCheck check = check_show_against_rig(show, rig);
  ASSERT_FALSE(check.ok());
  EXPECT_NE(check.errors.front().message.find("a digital cue switches channel 'key', which is analog"), std::string::npos)
      << check.errors.front().message;
}

TEST(ShowMarkers, AreReadInTimeOrderAndWrittenBackAsTheyWere) {
  const std::string text = std::string(kCueShow) + "markers:\n  - {time: 3.5, name: \"out\"}\n  - {time: 0.5, name: 12}\n";
  const playback::Show show = load_show_file(testing::write_temp_file("marker_show.yaml", text));
  ASSERT_EQ(show.markers.size(), 2U);
  EXPECT_EQ(show.markers[0].time, 0.5);
  EXPECT_EQ(show.markers[0].name, "12");  // a name that looks like a number stays a name
  EXPECT_EQ(show.markers[0].where.line, 11);
  EXPECT_EQ(show.markers[1].name, "out");
  const playback::Show again = load_show_text(show_text(show, "markers"), "again.yaml");
  ASSERT_EQ(again.markers.size(), 2U);
  EXPECT_EQ(again.markers[0].name, "12");
  EXPECT_EQ(again.markers[1].time, 3.5);
  EXPECT_EQ(load_show_text(show_text(again, "markers"), "again.yaml").markers[0].name, "12");
}

TEST(ShowMarkers, EachBadMarkerIsNamed) {
  const auto error = [](const std::string& markers) {
    return avar::testing::load_error(load_show_file, std::string(kCueShow) + "markers:\n" + markers, "marker_show.yaml");
  };
  EXPECT_EQ(error("  - {time: 5, name: late}\n"), ":10:12: expected marker 1 within the show, from 0 to 4 s, found 5 s");
  EXPECT_NE(error("  - {time: 1, name: a}\n  - {time: 2, name: a}\n").find("marker name 'a' is used twice (first at line 10)"),
            std::string::npos);
  EXPECT_EQ(error("  - {time: 1, name: \"\"}\n"), ":10:21: expected the name of marker 1 to be a name, found ''");
  EXPECT_NE(error("  - {time: 1}\n").find("name"), std::string::npos);
  EXPECT_NE(error("  - {time: 1, name: a, colour: red}\n").find("colour"), std::string::npos);
}

}  // namespace
}  // namespace avar::config
