// Ctrl-C on a real-time `avar play`, as a separate process: the first SIGINT eases the figure to
// rest and exits 130; a second one releases every servo at once.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>
#include <sstream>
#include <string>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/csv_rows.hpp"
#include "../support/osc_sender.hpp"
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

TEST(Interrupt, CtrlCEndsARecordedTakeAndKeepsIt) {
  const int port = testing::free_udp_port();
  const std::string take = testing::temp_path("take.yaml");
  testing::ChildProcess record({AVAR_BINARY, "record", "--rig", AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml", "--sim",
                                "--no-progress", "--priority", "0", "--input", "osc://127.0.0.1:" + std::to_string(port), "--out",
                                take});
  ASSERT_TRUE(record.started());
  ASSERT_NE(record.read_err_until("Ctrl-C ends the take").find("recording"), std::string::npos);
  testing::OscSender osc(port);
  for (int i = 0; i < 50; ++i) {  // a second of the jaw at 12
    osc.send("/avar/channel/jaw", 12.0f);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  record.signal(SIGINT);
  EXPECT_EQ(record.wait(), 0) << record.err();
  std::ifstream written(take);
  std::stringstream text;
  text << written.rdbuf();
  EXPECT_NE(text.str().find("jaw:"), std::string::npos) << text.str();
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
