#include "avar/control/control_mailbox.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace avar::control {
namespace {

TEST(ControlMailbox, KeepsTheLatestValueOfEachNamedControl) {
  ControlMailbox box({"jaw", "x", "jaw"});
  EXPECT_EQ(box.size(), 2u);
  EXPECT_EQ(box.read(box.find("jaw")).sequence, 0u);
  box.post("jaw", 0.25, false, 100);
  box.post("jaw", 0.5, false, 200);
  box.post("x", -0.5, true, 300);
  const ControlReading j = box.read(box.find("jaw"));
  EXPECT_DOUBLE_EQ(j.value, 0.5);
  EXPECT_EQ(j.sequence, 2u);
  EXPECT_EQ(j.arrived_ns, 200);
  EXPECT_FALSE(j.bipolar);
  EXPECT_TRUE(box.read(box.find("x")).bipolar);
}

TEST(ControlMailbox, CountsMessagesForControlsNothingMaps) {
  ControlMailbox box({"jaw"});
  box.post("nose", 1, false, 0);
  box.post("nose", 1, false, 0);
  EXPECT_EQ(box.unknown(), 2u);
  EXPECT_EQ(box.find("nose"), box.size());
}

// Writers on their own threads, a reader on another: every reading is a value some writer
// posted, and sequences never go back (ThreadSanitizer checks the rest).
TEST(ControlMailbox, WritersAndAReaderOnSeparateThreadsNeverSeeTornOrOlderState) {
  ControlMailbox box({"a", "b"});
  constexpr int kPosts = 20000;
  std::thread wa([&] {
    for (int i = 1; i <= kPosts; ++i) box.post("a", i, false, i);
  });
  std::thread wb([&] {
    for (int i = 1; i <= kPosts; ++i) box.post("b", -i, true, i);
  });
  std::uint64_t last = 0;
  while (last < kPosts) {
    const ControlReading r = box.read(box.find("a"));
    ASSERT_GE(r.sequence, last);
    last = r.sequence;
    if (r.sequence > 0) {
      ASSERT_GE(r.value, static_cast<double>(r.sequence));  // the value is at least as new
    }
  }
  wa.join();
  wb.join();
  EXPECT_DOUBLE_EQ(box.read(box.find("b")).value, -kPosts);
}

}  // namespace
}  // namespace avar::control
