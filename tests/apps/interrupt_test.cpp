// Ctrl-C on a real-time `avar play`, as a separate process: the first SIGINT eases the figure to
// rest and exits 130; a second one releases every servo at once.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"

namespace avar::app {
namespace {

std::vector<std::string> play_args(const std::string& trace) {
  return {AVAR_BINARY, "play", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rig",
          AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml", "--no-progress", "--trace", trace};
}

std::vector<std::string> last_row(const std::string& csv_path) {
  std::ifstream csv(csv_path);
  std::string line, last;
  while (std::getline(csv, line)) last = line;
  return testing::csv_cells(last);
}

TEST(Interrupt, FirstCtrlCEasesToRestAndExits130) {
  const std::string trace = testing::temp_path("trace.csv");
  testing::ChildProcess play(play_args(trace));
  ASSERT_TRUE(play.started());
  ASSERT_NE(play.read_err_until("Ctrl-C eases to rest").find("playing"), std::string::npos);
  play.signal(SIGINT);
  EXPECT_EQ(play.wait(), 130) << play.err();
  EXPECT_NE(play.err().find("interrupt: easing to rest"), std::string::npos) << play.err();
  EXPECT_NE(play.err().find("stopped: eased to rest after an interrupt"), std::string::npos) << play.err();
  const auto cells = last_row(trace);
  ASSERT_EQ(cells.size(), 8u + 8u * 3u);
  EXPECT_EQ(cells[1], "disabled");
  EXPECT_DOUBLE_EQ(std::stod(cells[9]), 0.0);               // jaw commanded at rest
  EXPECT_DOUBLE_EQ(std::stod(cells[8 + 6 * 3 + 1]), 20.0);  // lid_left at rest
}

TEST(Interrupt, SecondCtrlCReleasesAtOnce) {
  testing::ChildProcess play(play_args(testing::temp_path("trace.csv")));
  ASSERT_TRUE(play.started());
  play.read_err_until("Ctrl-C eases to rest");
  play.signal(SIGINT);
  // Signals of one kind do not queue: wait until the first was taken before sending the next.
  play.read_err_until("interrupt again to release");
  play.signal(SIGINT);
  EXPECT_EQ(play.wait(), 130) << play.err();
  EXPECT_NE(play.err().find("released: every actuator was let go at once"), std::string::npos) << play.err();
}

TEST(Interrupt, CtrlBackslashIsAnEstopFault) {
  const std::string trace = testing::temp_path("trace.csv");
  testing::ChildProcess play(play_args(trace));
  ASSERT_TRUE(play.started());
  play.read_err_until("Ctrl-C eases to rest");
  play.signal(SIGQUIT);
  EXPECT_EQ(play.wait(), 3) << play.err();
  EXPECT_NE(play.err().find(": e-stop; actuators took their fail-safe actions"), std::string::npos) << play.err();
  const auto cells = last_row(trace);
  ASSERT_EQ(cells.size(), 8u + 8u * 3u);
  EXPECT_EQ(cells[1], "faulted");
  EXPECT_DOUBLE_EQ(std::stod(cells[9]), 0.0);  // jaw: fail-safe "rest" (the default)
}

}  // namespace
}  // namespace avar::app
