#include "avar/config/show_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "../support/input_errors.hpp"
#include "../support/temp_file.hpp"

namespace avar::config {
namespace {

std::string show_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }
using avar::testing::replace;


std::string write_temp(const std::string& text) { return testing::write_temp_file("show.yaml", text); }

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

TEST(ShowFile, LoadsTheLongTrackFormWithEveryCurveField) {
  const playback::Show show = load_show_file(write_temp(R"(duration: 10
tracks:
  a:
    extrapolation: linear
    auto_smoothing: continuous_acceleration
    cycles: {before: mirror, after: repeat_offset, before_count: 2, after_count: 0}
    keys:
      - {time: 0, value: 0, interpolation: bezier, left_type: vector, right_type: auto}
      - {time: 1, value: 5, interpolation: elastic, easing: ease_in_out, amplitude: 2, period: 0.25, left_type: auto_clamped,
         right: [1.2, 6], right_type: aligned}
      - {time: 2, value: 1, interpolation: back, back: 2.5}
      - {time: 3, value: 2, interpolation: hermite, out_slope: 1.5}
      - {time: 4, value: 0, interpolation: kochanek_bartels, in_slope: -2, tension: 0.5, continuity: -0.5, bias: 0.25}
      - {time: 5, value: 3, interpolation: cardinal, tension: 0.3}
      - {time: 6, value: 1, interpolation: catmull_rom}
      - {time: 7, value: 4, interpolation: bspline}
      - {time: 8, value: 0, interpolation: constant}
      - {time: 9, value: 2, interpolation: step}
  b: [{time: 0, value: 1}]
)"));
  ASSERT_EQ(show.tracks.size(), 2u);
  const playback::RawCurve& raw = show.tracks[0].raw;
  EXPECT_EQ(raw.extrapolation, playback::Extrapolation::linear);
  EXPECT_EQ(raw.auto_smoothing, playback::AutoSmoothing::continuous_acceleration);
  EXPECT_EQ(raw.cycles.before, playback::CycleMode::mirror);
  EXPECT_EQ(raw.cycles.after, playback::CycleMode::repeat_offset);
  EXPECT_EQ(raw.cycles.before_count, 2);
  EXPECT_EQ(raw.keys[0].left_type, playback::HandleType::vector);
  EXPECT_EQ(raw.keys[0].right_type, playback::HandleType::automatic);
  EXPECT_EQ(raw.keys[1].interpolation, playback::Interpolation::elastic);
  EXPECT_EQ(raw.keys[1].easing, playback::Easing::ease_in_out);
  EXPECT_DOUBLE_EQ(raw.keys[1].amplitude, 2);
  EXPECT_DOUBLE_EQ(raw.keys[1].period, 0.25);
  EXPECT_EQ(raw.keys[1].right_type, playback::HandleType::aligned);
  EXPECT_DOUBLE_EQ(raw.keys[2].back, 2.5);
  EXPECT_DOUBLE_EQ(*raw.keys[3].out_slope, 1.5);
  EXPECT_DOUBLE_EQ(*raw.keys[4].in_slope, -2);
  EXPECT_DOUBLE_EQ(raw.keys[4].continuity, -0.5);
  EXPECT_EQ(raw.keys[8].interpolation, playback::Interpolation::step);
  EXPECT_EQ(raw.keys[9].interpolation, playback::Interpolation::step);
  EXPECT_EQ(show.tracks[0].curve.evaluate(1), 5);
  EXPECT_EQ(show.tracks[1].curve.evaluate(3), 1);
}

TEST(ShowFile, RejectsMalformedCurveFieldsWithWhereAndWhat) {
  const std::string head = "duration: 3\ntracks:\n  jaw:\n";
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, tension: 0.5}\n"),
            ":4:36: field 'tension' does not belong to a key with linear interpolation; expected it only on cardinal and "
            "kochanek_bartels keys");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: sine, back: 2}\n"),
            ":4:54: field 'back' does not belong to a key with sine interpolation; expected it only on back keys");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, easing: ease_in}\n"),
            ":4:35: field 'easing' does not belong to a key with linear interpolation; expected it only on keys with an easing "
            "interpolation (sine, quad, cubic, quart, quint, expo, circ, back, bounce, elastic)");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, in_slope: 2}\n"),
            ":4:37: field 'in_slope' does not belong to a key with linear interpolation; expected it only on keys that end a "
            "hermite segment (after a hermite key)");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: quad, easing: sideways}\n"),
            ":4:56: unknown easing 'sideways'; expected one of: auto, ease_in, ease_out, ease_in_out");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, left_type: smooth}\n"),
            ":4:38: unknown handle type 'smooth'; expected one of: free, aligned, vector, auto, auto_clamped");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: hermite}\n    - {time: 1, value: 2}\n"),
            ":4:7: the key at 0 s starts a hermite segment but has no out_slope; expected out_slope: <units per second>");
  EXPECT_EQ(show_error(head + "    extrapolation: cyclic\n    keys: [{time: 0, value: 1}]\n"),
            ":4:20: unknown extrapolation 'cyclic'; expected one of: constant, linear");
  EXPECT_EQ(show_error(head + "    cycles: {after: pingpong}\n    keys: [{time: 0, value: 1}]\n"),
            ":4:21: unknown cycle mode 'pingpong'; expected one of: none, repeat, repeat_offset, mirror");
  EXPECT_EQ(show_error(head + "    cycles: {after: repeat, after_count: -1}\n    keys: [{time: 0, value: 1}]\n"),
            ":4:42: expected a cycle count of 0 (forever) or more, found '-1'");
  EXPECT_EQ(show_error(head + "    auto_smoothing: lots\n    keys: [{time: 0, value: 1}]\n"),
            ":4:21: unknown auto_smoothing 'lots'; expected one of: none, continuous_acceleration");
  EXPECT_EQ(show_error(head + "    extrapolation: linear\n"), ":4:5: missing field 'keys' in track 'jaw'");
  EXPECT_EQ(show_error(head + "    keyz: []\n"),
            ":4:5: unknown field 'keyz' in track 'jaw'; expected one of: extrapolation, cycles, auto_smoothing, keys");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: elastic, period: .nan}\n"),
            ":4:59: expected the period (seconds) to be a finite number, found '.nan'");
}

// Blender's own FCurve.evaluate on a dense grid (tests/playback/golden, made by
// generate_golden.py): every channel of the golden show must match every sample within
// 1e-3 + 1e-4 x the channel's range, before, between and after its keys.
TEST(ShowFile, ReproducesBlenderGoldenCurves) {
  const std::string dir = AVAR_SOURCE_DIR "/tests/playback/golden/";
  const playback::Show show = load_show_file(dir + "blender_curves.yaml");
  std::ifstream csv(dir + "blender_curves.csv");
  ASSERT_TRUE(csv) << "missing " << dir << "blender_curves.csv";
  std::string line;
  std::getline(csv, line);
  std::vector<std::string> names;
  {
    std::stringstream header(line);
    std::string name;
    std::getline(header, name, ',');  // seconds
    while (std::getline(header, name, ',')) names.push_back(name);
  }
  std::vector<double> times;
  std::vector<std::vector<double>> expected(names.size());
  while (std::getline(csv, line)) {
    std::stringstream row(line);
    std::string cell;
    std::getline(row, cell, ',');
    times.push_back(std::stod(cell));
    for (auto& column : expected) {
      std::getline(row, cell, ',');
      column.push_back(std::stod(cell));
    }
  }
  ASSERT_EQ(names.size(), show.tracks.size());
  ASSERT_GT(times.size(), 300u);
  for (std::size_t c = 0; c < names.size(); ++c) {
    const playback::Track& track = show.tracks[c];
    ASSERT_EQ(track.channel, names[c]);
    const auto [low, high] = std::minmax_element(expected[c].begin(), expected[c].end());
    const double tolerance = 1e-3 + 1e-4 * (*high - *low);
    playback::CurveCursor cursor;
    double worst = 0, worst_time = 0, worst_value = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const double value = track.curve.evaluate(times[i], cursor);
      EXPECT_EQ(value, track.curve.evaluate(times[i])) << names[c] << " at " << times[i] << " s";
      const double error = std::abs(value - expected[c][i]);
      if (!(error <= worst)) worst = error, worst_time = times[i], worst_value = value;
    }
    EXPECT_LE(worst, tolerance) << names[c] << ": worst at " << worst_time << " s (frame " << worst_time * 24 << "): avar "
                                << worst_value << ", Blender " << expected[c][static_cast<std::size_t>(std::find(times.begin(), times.end(), worst_time) - times.begin())];
  }
}

// At a key's time every golden curve returns that key's value, as Blender does, whether the time
// is the key's own double, that time on avar sample's nanosecond grid, or up to 0.9 us either side
// (avar's key snap is 1 us; Blender's 0.0001 frame is 4 us at 24 fps): a constant segment before
// a key at 11/6 s must not show the previous key's value there. Random access and a cursor coming
// from a tick before agree.
TEST(ShowFile, GoldenCurvesReturnEachKeysValueAtItsTime) {
  const playback::Show show = load_show_file(AVAR_SOURCE_DIR "/tests/playback/golden/blender_curves.yaml");
  ASSERT_GT(show.tracks.size(), 40u);
  std::size_t checked = 0;
  for (const playback::Track& track : show.tracks) {
    for (const playback::RawKey& key : track.raw.keys) {
      const double on_grid = std::round(key.time * 1e9) / 1e9;
      for (const double t : {key.time, on_grid, std::nextafter(key.time, -1e9), std::nextafter(key.time, 1e9), key.time - 0.9e-6,
                             key.time + 0.9e-6}) {
        const double tolerance = 1e-9 * std::max(1.0, std::abs(key.value));
        EXPECT_NEAR(track.curve.evaluate(t), key.value, tolerance)
            << track.channel << ": key at " << key.time << " s sampled at " << t << " s";
        playback::CurveCursor cursor;
        track.curve.evaluate(key.time - 1.0 / 60, cursor);  // the tick before
        EXPECT_EQ(track.curve.evaluate(t, cursor), track.curve.evaluate(t))
            << track.channel << ": key at " << key.time << " s sampled at " << t << " s";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000u);
}

TEST(ShowFile, BundledExampleLoads) {
  const playback::Show show = load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  EXPECT_EQ(show.tracks.size(), 8u);
  const playback::Show tour = load_show_file(AVAR_SOURCE_DIR "/examples/shows/curves-tour.yaml");
  EXPECT_EQ(tour.tracks.size(), 8u);
}

TEST(ShowFile, RejectsEachBadInputWithWhereAndWhat) {
  const std::string head = "duration: 3\ntracks:\n  jaw:\n";
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1}\n    - {time: 0, value: 2}\n"),
            ":5:7: key time 0 s is not after the previous key's 0 s; key times must strictly increase");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: cubical}\n"),
            ":4:42: unknown interpolation 'cubical'; expected one of: constant (or step), linear, bezier, sine, quad, cubic, quart, "
            "quint, expo, circ, back, bounce, elastic, hermite, catmull_rom, cardinal, kochanek_bartels, bspline");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolaton: step}\n"),
            ":4:27: unknown field 'interpolaton' in a key of track 'jaw'; expected one of: time, value, interpolation, left, right, "
            "left_type, right_type, easing, back, amplitude, period, in_slope, out_slope, tension, continuity, bias");
  // A key outside the show is no error: it shapes the curve inside (keys_outside_show_test.cpp).
  EXPECT_EQ(show_error(head + "    - {time: -0.0333333, value: 1}\n    - {time: 4, value: 2}\n"), "");
  EXPECT_EQ(show_error(head + "    - {time: .inf, value: 1}\n"),
            ":4:14: expected the key time (seconds) to be a finite number, found '.inf'");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: .nan}\n"), ":4:24: expected the key value to be a finite number, found '.nan'");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, interpolation: bezier, right_type: free}\n    - {time: 1, value: 2}\n"),
            ":4:7: the right handle of the key at 0 s is free but not given; expected right: [time, value], or right_type auto, "
            "auto_clamped or vector to compute it");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1, right: [1, 2, 3]}\n"),
            ":4:34: expected the right handle to be [time, value], found a list");
  EXPECT_EQ(show_error(head + "    - {value: 1}\n"), ":4:7: missing field 'time' in a key of track 'jaw'");
  EXPECT_EQ(show_error(head + "    []\n"), ":3:3: track 'jaw' has no keys; expected at least one");
  EXPECT_EQ(show_error(head + "    - {time: 0, value: 1}\n  jaw:\n    - {time: 0, value: 1}\n"),
            ":5:3: duplicate key 'jaw' (first at line 3, column 3); expected each key once in a map");
  EXPECT_EQ(show_error("duration: -1\ntracks: {}\n"), ":1:11: expected the duration to be more than 0 seconds, found '-1'");
  EXPECT_EQ(show_error("tracks: {}\n"), ":1:1: missing field 'duration' in the show file");
  EXPECT_EQ(show_error("duration: 3\ntracks:\n  jaw: 5\n"), ":3:8: expected the keys of track 'jaw' to be a list, found '5'");
  EXPECT_EQ(show_error(""), ":1:1: the file is empty; expected a YAML map");
}

}  // namespace
}  // namespace avar::config
