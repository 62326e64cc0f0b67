// OSC addresses and arguments to controls: the table of what is taken and what is ignored.
#include "avar/inputs/osc_dispatch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace avar::inputs {
namespace {

struct OscDispatchRow {
  std::string path;
  std::string types;
  std::vector<double> values;
  bool taken;
  std::string control;
  double value;
};

TEST(OscDispatch, Table) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<OscDispatchRow> rows{
      {"/avar/control/jaw", "f", {0.5}, true, "jaw", 0.5},
      {"/avar/control/jaw", "d", {0.25}, true, "jaw", 0.25},
      {"/avar/control/jaw", "i", {1}, true, "jaw", 1.0},
      {"/avar/control/jaw", "h", {-3}, true, "jaw", -3.0},
      {"/avar/control/blink", "T", {0}, true, "blink", 1.0},
      {"/avar/control/blink", "F", {0}, true, "blink", 0.0},
      {"/avar/control/jaw", "f", {1.7}, true, "jaw", 1.7},  // not clamped: the mapping stage clamps
      {"/avar/control/left_eye.x-2", "f", {0.1}, true, "left_eye.x-2", 0.1},
      {"/avar/channel/neck", "f", {-35.5}, true, "channel/neck", -35.5},  // channel units
      {"/avar/channel/arm.elbow", "d", {120}, true, "channel/arm.elbow", 120.0},
      // Ignored.
      {"/avar/control/jaw", "", {}, false, "", 0},
      {"/avar/control/jaw", "ff", {0.1, 0.2}, false, "", 0},
      {"/avar/control/jaw", "s", {0}, false, "", 0},
      {"/avar/control/jaw", "N", {0}, false, "", 0},
      {"/avar/control/jaw", "I", {0}, false, "", 0},
      {"/avar/control/jaw", "b", {0}, false, "", 0},
      {"/avar/control/jaw", "f", {nan}, false, "", 0},
      {"/avar/control/jaw", "d", {inf}, false, "", 0},
      {"/avar/control/jaw", "d", {-inf}, false, "", 0},
      {"/avar/control/", "f", {0.5}, false, "", 0},
      {"/avar/channel/", "f", {0.5}, false, "", 0},
      {"/avar/control/ja w", "f", {0.5}, false, "", 0},
      {"/avar/control/jaw/x", "f", {0.5}, false, "", 0},
      {"/avar/control/j*", "f", {0.5}, false, "", 0},
      {"/avar/control/jäw", "f", {0.5}, false, "", 0},
      {"/avar/control", "f", {0.5}, false, "", 0},
      {"/avar/controls/jaw", "f", {0.5}, false, "", 0},
      {"/AVAR/control/jaw", "f", {0.5}, false, "", 0},
      {"/other/jaw", "f", {0.5}, false, "", 0},
      {"", "f", {0.5}, false, "", 0},
      {"/avar/control/" + std::string(kMaxOscControlName + 1, 'a'), "f", {0.5}, false, "", 0},
  };
  for (const OscDispatchRow& row : rows) {
    SCOPED_TRACE(row.path + " ," + row.types);
    const auto c = osc_control(row.path, row.types, row.values);
    ASSERT_EQ(c.has_value(), row.taken);
    if (!c) continue;
    EXPECT_EQ(c->control, row.control);
    EXPECT_DOUBLE_EQ(c->value, row.value);
  }
  const std::string longest = "/avar/control/" + std::string(kMaxOscControlName, 'a');
  EXPECT_TRUE(osc_control(longest, "f", std::vector<double>{0.5}).has_value());
}

TEST(OscDispatch, ControlNameIsAViewIntoThePath) {
  const std::string path = "/avar/channel/jaw";
  const auto c = osc_control(path, "f", std::vector<double>{1.0});
  ASSERT_TRUE(c);
  EXPECT_EQ(c->control.data(), path.data() + 6);
}

}  // namespace
}  // namespace avar::inputs
