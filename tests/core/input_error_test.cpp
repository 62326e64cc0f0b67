#include "avar/core/input_error.hpp"

#include <gtest/gtest.h>

namespace avar {
namespace {

TEST(InputError, NamesFileLineAndColumn) {
  InputError e({"shows/a.yaml", 12, 5}, "expected a number, found 'abc'");
  EXPECT_STREQ(e.what(), "shows/a.yaml:12:5: expected a number, found 'abc'");
  EXPECT_EQ(e.where().line, 12);
}

TEST(InputError, LeavesOutUnknownParts) {
  EXPECT_EQ(to_string(SourceLocation{"rig.yaml", 0, 0}), "rig.yaml");
  EXPECT_EQ(to_string(SourceLocation{"rig.yaml", 3, 0}), "rig.yaml:3");
  EXPECT_EQ(to_string(SourceLocation{"", 0, 0}), "<input>");
}

}  // namespace
}  // namespace avar
