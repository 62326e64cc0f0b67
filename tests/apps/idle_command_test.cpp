// `avar idle` and `avar play --idle` end to end on the simulator (--fast), read back from the
// trace: no channel leaves its range or exceeds its speed, a seed repeats a run exactly, the show
// keeps its channels while it plays and idle has them before and after.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/rig_file.hpp"

namespace avar {
namespace {

const std::string kIdleRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml";

struct IdleTrace {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string text;

  explicit IdleTrace(const std::string& path) {
    std::ifstream in(path);
    std::stringstream all;
    all << in.rdbuf();
    text = all.str();
    std::istringstream lines(text);
    rows = testing::csv_rows(lines);
    header = rows.front();
    rows.erase(rows.begin());
  }
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw std::runtime_error("no column " + name);
  }
  double at(std::size_t row, const std::string& name) const { return std::stod(rows[row][column(name)]); }
  std::size_t first_running() const {
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (rows[k][column("phase")] == "running") return k;
    return rows.size();
  }
};

TEST(IdleCommand, IdleAloneStaysWithinEveryLimitAndASeedRepeatsIt) {
  const rig::Rig rig = config::load_rig_file(kIdleRig);
  const std::string a = testing::temp_path("a.csv"), b = testing::temp_path("b.csv"), c = testing::temp_path("c.csv");
  const auto run = [&](const std::string& seed, const std::string& trace) {
    return testing::run_avar(
        {"idle", "--rig", kIdleRig, "--sim", "--fast", "--duration", "20", "--seed", seed, "--trace", trace});
  };
  const testing::CliResult first = run("3", a);
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_NE(first.out.find("idle: seed 3"), std::string::npos) << first.out;
  ASSERT_EQ(run("3", b).code, 0);
  ASSERT_EQ(run("4", c).code, 0);
  const IdleTrace trace(a);
  EXPECT_EQ(trace.text, IdleTrace(b).text);
  EXPECT_NE(trace.text, IdleTrace(c).text);

  const double dt = 1.0 / rig.rate_hz;
  double lid_lowest = 100;
  for (const rig::ChannelSpec& ch : rig.channels) {
    for (std::size_t k = 0; k < trace.rows.size(); ++k) {
      const double v = trace.at(k, ch.name + ".command");
      ASSERT_GE(v, ch.min) << ch.name;
      ASSERT_LE(v, ch.max) << ch.name;
      if (k > 0) {
        ASSERT_LE(std::abs(v - trace.at(k - 1, ch.name + ".command")), ch.max_velocity * dt * (1 + 1e-9))
            << ch.name << " tick " << k;
      }
      if (ch.name == "lid_left") lid_lowest = std::min(lid_lowest, v);
    }
  }
  EXPECT_LT(lid_lowest, 10);  // the lids blinked
}

TEST(IdleCommand, LookAtGazeConvergesTheEyesOnNearTargetsThroughTheKinematics) {
  const std::string rig_path = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-eyes.yaml";
  const rig::Rig rig = config::load_rig_file(rig_path);
  const std::string path = testing::temp_path("look_at.csv");
  const testing::CliResult run =
      testing::run_avar({"idle", "--rig", rig_path, "--sim", "--fast", "--duration", "20", "--seed", "5", "--trace", path});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("saccades (eyes aimed: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" 0 failed)"), std::string::npos) << run.out;
  const IdleTrace trace(path);
  // Each eye turns inwards by atan(0.032 / distance): about 0.9° for a far target (2 m), 6.1° for
  // a near one (0.3 m), so the two pans differ by 1.8° or up to 12.2° (less off to a side).
  double widest = 0, narrowest = 1e9;
  for (std::size_t k = trace.first_running() + 100; k < trace.rows.size(); ++k) {
    if (trace.rows[k][trace.column("phase")] != "running") break;
    const double apart = trace.at(k, "eye_r_pan.target") - trace.at(k, "eye_l_pan.target");
    widest = std::max(widest, apart);
    narrowest = std::min(narrowest, apart);
    for (const rig::ChannelSpec& ch : rig.channels) {
      ASSERT_GE(trace.at(k, ch.name + ".command"), ch.min) << ch.name;
      ASSERT_LE(trace.at(k, ch.name + ".command"), ch.max) << ch.name;
    }
  }
  EXPECT_GT(widest, 9);
  EXPECT_LT(widest, 12.5);
  EXPECT_GT(narrowest, 1.0);
  EXPECT_LT(narrowest, 1.9);
}

TEST(IdleCommand, PlayWithIdleKeepsTheShowOnItsChannelsAndIdleBeforeAndAfter) {
  const std::string show = testing::write_temp_file("roll.yaml",
                                                    "name: roll\nduration: 4\ntracks:\n"
                                                    "  neck_roll:\n    - {time: 0, value: 5}\n    - {time: 2, value: -5}\n"
                                                    "    - {time: 4, value: 5}\n"
                                                    "  jaw:\n    - {time: 0, value: 0}\n    - {time: 2, value: 20}\n"
                                                    "    - {time: 4, value: 0}\n");
  const std::string plain_path = testing::temp_path("plain.csv"), idle_path = testing::temp_path("idle.csv");
  const testing::CliResult plain = testing::run_avar({"play", show, "--rig", kIdleRig, "--sim", "--fast", "--trace", plain_path});
  ASSERT_EQ(plain.code, 0) << plain.err;
  const testing::CliResult idle = testing::run_avar({"play", show, "--rig", kIdleRig, "--sim", "--fast", "--idle", "--seed", "8",
                                                     "--idle-before", "2", "--idle-after", "2", "--trace", idle_path});
  ASSERT_EQ(idle.code, 0) << idle.err;
  const IdleTrace p(plain_path), q(idle_path);
  const std::size_t p0 = p.first_running(), q0 = q.first_running();
  ASSERT_LT(p0, p.rows.size());
  ASSERT_LT(q0, q.rows.size());
  const std::size_t lead = 100;  // 2 s at 50 Hz
  // While the show plays, its channels are the show's, tick for tick.
  for (std::size_t k = 0; k < 200; ++k)
    for (const std::string ch : {"neck_roll", "jaw"}) {
      ASSERT_NEAR(q.at(q0 + lead + k, ch + ".target"), p.at(p0 + k, ch + ".target"), 1e-6) << ch << " show tick " << k;
    }
  // Before it, idle moves neck_roll about (its noise) where the show would hold 5.
  double moved = 0;
  for (std::size_t k = 50; k < 80; ++k) moved = std::max(moved, std::abs(q.at(q0 + k, "neck_roll.target") - 5));
  EXPECT_GT(moved, 0.5);
  // And the eyes, which the show leaves alone, saccade throughout.
  double eyes_low = 1e9, eyes_high = -1e9;
  for (std::size_t k = q0; k < q.rows.size(); ++k) {
    eyes_low = std::min(eyes_low, q.at(k, "eyes_pan.target"));
    eyes_high = std::max(eyes_high, q.at(k, "eyes_pan.target"));
  }
  EXPECT_GT(eyes_high - eyes_low, 5);
  EXPECT_GE(q.rows.size(), p.rows.size() + 2 * lead - 5);
}

TEST(IdleCommand, IdleNeedsAnIdleSectionAndSeedNeedsIdle) {
  const std::string rig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-head.yaml";
  const testing::CliResult none = testing::run_avar({"idle", "--rig", rig, "--sim", "--fast", "--duration", "1"});
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("needs an idle: section"), std::string::npos) << none.err;
  const testing::CliResult forever = testing::run_avar({"idle", "--rig", kIdleRig, "--sim", "--fast"});
  EXPECT_EQ(forever.code, 2);
  EXPECT_NE(forever.err.find("--duration"), std::string::npos) << forever.err;
  const std::string show = std::string(AVAR_SOURCE_DIR) + "/examples/shows/hello-head.yaml";
  EXPECT_EQ(testing::run_avar({"play", show, "--rig", kIdleRig, "--sim", "--fast", "--seed", "3"}).code, 2);
}

}  // namespace
}  // namespace avar
