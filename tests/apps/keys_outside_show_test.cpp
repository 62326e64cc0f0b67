// A show with keys before 0 and after its end (as a Blender scene keyed from frame 0 exports it),
// through the command line: `avar sample` reaches the keys, `avar check` accepts the show, `avar
// play` eases into the curve's value at 0 and plays from there.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

// jaw: 0 at -0.5 s, 20 at 0.5 s (so 10 at 0), 30 at 2.5 s, past the 2 s end (so 27.5 there).
const char* const kOutsideKeysShow = R"(name: keyed-early
duration: 2
tracks:
  jaw:
    - {time: -0.5, value: 0}
    - {time: 0.5, value: 20}
    - {time: 2.5, value: 30}
)";

const std::string kOutsideRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

TEST(KeysOutsideShowCli, SampleReachesTheKeysBeforeAndAfterTheShow) {
  const std::string show = testing::write_temp_file("early.yaml", kOutsideKeysShow);
  const auto r = testing::run_avar({"sample", show, "--from", "-0.5", "--to", "2.5", "--step", "0.5"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto rows = testing::csv_rows(r.out);
  ASSERT_EQ(rows.size(), 8u);
  const std::vector<double> expected{0, 10, 20, 22.5, 25, 27.5, 30};
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_DOUBLE_EQ(std::strtod(rows[i + 1][1].c_str(), nullptr), expected[i]) << i;
}

TEST(KeysOutsideShowCli, CheckAcceptsAndPlayEasesIntoTheValueAtZero) {
  const std::string show = testing::write_temp_file("early.yaml", kOutsideKeysShow);
  const auto checked = testing::run_avar({"check", show, "--rig", kOutsideRig});
  EXPECT_EQ(checked.code, kExitOk) << checked.err << checked.out;
  const std::string trace = testing::temp_path("early-trace.csv");
  const auto played = testing::run_avar({"play", show, "--rig", kOutsideRig, "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(played.code, kExitOk) << played.err << played.out;
  std::ifstream csv(trace);
  const auto rows = testing::csv_rows(csv);
  ASSERT_GT(rows.size(), 2u);
  ASSERT_EQ(rows[0][8], "jaw.target");
  ASSERT_EQ(rows[0][9], "jaw.command");
  // The last tick of the soft start has brought the jaw to the show's value at 0; the first
  // running tick aims there; the show ends on the curve's value at 2 s.
  std::size_t first_running = 0, last_running = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i][1] != "running") continue;
    if (first_running == 0) first_running = i;
    last_running = i;
  }
  ASSERT_GT(first_running, 1u);
  EXPECT_EQ(rows[first_running - 1][1], "homing");
  EXPECT_NEAR(std::strtod(rows[first_running - 1][9].c_str(), nullptr), 10, 1e-6);
  EXPECT_NEAR(std::strtod(rows[first_running][8].c_str(), nullptr), 10, 0.2);  // one tick into the show
  EXPECT_NEAR(std::strtod(rows[last_running][8].c_str(), nullptr), 27.5, 0.2);
}

}  // namespace
}  // namespace avar::app
