#include "avar/config/show_file.hpp"

#include <gtest/gtest.h>

#include "../support/temp_file.hpp"

namespace avar::config {
namespace {

std::string write_temp(const std::string& text) { return testing::write_temp_file("show.yaml", text); }

/// The error for a show text, without the file name ("" when it loads).
std::string error_of(const std::string& text) {
  const std::string path = write_temp(text);
  try {
    load_show_file(path);
    return "";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    return msg.substr(path.size());
  }
}

TEST(ShowFile, LoadsTracksKeysInterpolationsAndHandles) {
  const playback::Show show = load_show_file(write_temp(R"(name: s
duration: 3
loop: true
tracks:
  jaw:
    - {time: 0, value: 1}
    - {time: 1, value: 5, interpolation: bezier, right: [1.5, 5]}
    - {time: 2, value: 0, interpolation: step, left: [1.5, 0]}
  pan:
    - {time: 0.5, value: -3}
)"));
  EXPECT_EQ(show.name, "s");
  EXPECT_DOUBLE_EQ(show.duration, 3);
  EXPECT_TRUE(show.loop);
  ASSERT_EQ(show.tracks.size(), 2u);
  EXPECT_EQ(show.tracks[0].channel, "jaw");
  EXPECT_EQ(show.tracks[0].raw.keys[1].interpolation, playback::Interpolation::bezier);
  EXPECT_DOUBLE_EQ(show.tracks[0].raw.keys[1].right->time, 1.5);
  EXPECT_EQ(show.tracks[0].raw.keys[2].where.line, 8);
  EXPECT_DOUBLE_EQ(show.tracks[0].curve.evaluate(0.5), 3);
  EXPECT_DOUBLE_EQ(show.tracks[1].curve.evaluate(2), -3);
}

TEST(ShowFile, BundledExampleLoads) {
  const playback::Show show = load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  EXPECT_EQ(show.tracks.size(), 8u);
}

TEST(ShowFile, RejectsEachBadInputWithWhereAndWhat) {
  const std::string head = "duration: 3\ntracks:\n  jaw:\n";
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1}\n    - {time: 0, value: 2}\n"),
            ":5:7: key time 0 s is not after the previous key's 0 s; key times must strictly increase");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1, interpolation: cubic}\n"),
            ":4:42: unknown interpolation 'cubic'; expected one of: step, linear, bezier");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1, interpolaton: step}\n"),
            ":4:27: unknown field 'interpolaton' in a key of track 'jaw'; expected one of: time, value, interpolation, left, right");
  EXPECT_EQ(error_of(head + "    - {time: 4, value: 1}\n"), ":4:14: key time 4 s is outside the show, which runs from 0 to 3 s");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: .nan}\n"), ":4:24: expected the key value to be a finite number, found '.nan'");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1, interpolation: bezier}\n    - {time: 1, value: 2}\n"),
            ":4:7: the key at 0 s starts a bezier segment but has no right handle; expected right: [time, value]");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1, right: [1, 2, 3]}\n"),
            ":4:34: expected the right handle to be [time, value], found a list");
  EXPECT_EQ(error_of(head + "    - {value: 1}\n"), ":4:7: missing field 'time' in a key of track 'jaw'");
  EXPECT_EQ(error_of(head + "    []\n"), ":3:3: track 'jaw' has no keys; expected at least one");
  EXPECT_EQ(error_of(head + "    - {time: 0, value: 1}\n  jaw:\n    - {time: 0, value: 1}\n"),
            ":5:3: channel 'jaw' has two tracks; expected one track per channel");
  EXPECT_EQ(error_of("duration: -1\ntracks: {}\n"), ":1:11: expected the duration to be more than 0 seconds, found '-1'");
  EXPECT_EQ(error_of("tracks: {}\n"), ":1:1: missing field 'duration' in the show file");
  EXPECT_EQ(error_of("duration: 3\ntracks:\n  jaw: 5\n"), ":3:8: expected the keys of track 'jaw' to be a list, found '5'");
  EXPECT_EQ(error_of(""), ":1:1: the file is empty; expected a YAML map");
}

}  // namespace
}  // namespace avar::config
