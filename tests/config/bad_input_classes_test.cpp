// One malformed-file class at a time, each refused with file:line:col and what was expected (the
// seeded sweep in tests/apps/bad_input_sweep_test.cpp runs them on every bundled example). The
// duplicate-key, alias and huge-path-point cases are regressions found by that sweep.
#include <gtest/gtest.h>

#include <string>

#include "../support/input_errors.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"

namespace avar::config {
namespace {

std::string classes_show_error(const std::string& text) { return avar::testing::load_error(load_show_file, text, "show.yaml"); }

const std::string kClassesHead = "duration: 3\ntracks:\n  jaw:\n";

TEST(BadInputClasses, DuplicateKeysAreRefusedAtTheSecond) {
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 0, value: 1, value: 2}\n"),
            ":4:27: duplicate key 'value' (first at line 4, column 17); expected each key once in a map");
  EXPECT_EQ(classes_show_error("duration: 3\nduration: 4\ntracks: {}\n"),
            ":2:1: duplicate key 'duration' (first at line 1, column 1); expected each key once in a map");
  // In a rig too: every file goes through the same reader.
  EXPECT_EQ(avar::testing::load_error(load_rig_file, "name: r\nname: s\n", "rig.yaml"),
            ":2:1: duplicate key 'name' (first at line 1, column 1); expected each key once in a map");
}

TEST(BadInputClasses, AliasBombsAndSelfContainingAnchorsAreRefused) {
  std::string bomb = "[&l0 [1, 1, 1, 1, 1, 1, 1, 1, 1]";
  for (int level = 1; level < 9; ++level) {
    bomb += ", &l" + std::to_string(level) + " [";
    for (int i = 0; i < 9; ++i) bomb += (i ? ", *l" : "*l") + std::to_string(level - 1);
    bomb += "]";
  }
  bomb += "]";
  const std::string expands = "values (aliases repeating an anchor); expected a rig or show without such nesting";
  const std::string bombed = classes_show_error(kClassesHead + "    - {time: 0, value: " + bomb + "}\n");
  EXPECT_EQ(bombed.rfind(":4:", 0), 0u) << bombed;
  EXPECT_NE(bombed.find(expands), std::string::npos) << bombed;
  const std::string cycle = classes_show_error("duration: 3\nloop: &a [*a]\ntracks: {}\n");
  EXPECT_EQ(cycle.rfind(":2:", 0), 0u) << cycle;
}

TEST(BadInputClasses, NumbersThatAreNotFiniteHugeOrCarryUnitsAreRefused) {
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 0, value: .nan}\n"),
            ":4:24: expected the key value to be a finite number, found '.nan'");
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 1e999, value: 0}\n"),
            ":4:14: expected the key time (seconds) to be a finite number, found '1e999'");
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 1.5s, value: 0}\n"),
            ":4:14: expected the key time (seconds) to be a finite number, found '1.5s'");
  // A path point at 1e308 used to hang the arc-length quadrature.
  const std::string path = classes_show_error(R"(duration: 4
targets:
  gaze:
    path:
      points: [[1, 0, 0.4], [1, -1e308, 0.5], [1, 0.5, 0.4]]
      from: 0
      to: 4
)");
  EXPECT_EQ(path, ":5:29: expected a path point of finite numbers within ±1e6 m");
}

TEST(BadInputClasses, WrongTypesUnknownFieldsAndTruncationAreRefused) {
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 0, value: [1, 2]}\n"),
            ":4:24: expected the key value to be a number, found a list");
  EXPECT_EQ(classes_show_error(kClassesHead + "    - {time: 0, value: 1, bogus: 1}\n"),
            ":4:27: unknown field 'bogus' in a key of track 'jaw'; expected one of: time, value, interpolation, left, right, "
            "left_type, right_type, easing, back, amplitude, period, in_slope, out_slope, tension, continuity, bias");
  const std::string truncated = classes_show_error(kClassesHead + "    - {time: 0, val");
  EXPECT_EQ(truncated.rfind(":", 0), 0u) << truncated;
  EXPECT_NE(truncated.find("malformed YAML"), std::string::npos) << truncated;
}

}  // namespace
}  // namespace avar::config
