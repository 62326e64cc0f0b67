// `avar sample`: the CSV it writes (grid, columns, exact numbers, values off the keys) and its
// refusals, in-process and as the real binary.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/cli.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kSampledShow = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";

// Two tracks: a ramp (linear 0 -> 10 over 1 s, then held) and a step channel.
const char* const kSmallShow = R"(name: small
duration: 2
tracks:
  ramp:
    - {time: 0.5, value: 0}
    - {time: 1.5, value: 10}
  switch:
    - {time: 0.0, value: 1, interpolation: step}
    - {time: 1.0, value: -2}
)";

using Result = testing::CliResult;
Result sample(std::vector<std::string> args) {
  args.insert(args.begin(), "sample");
  return testing::run_avar(std::move(args));
}

TEST(SampleCommand, WritesEveryChannelOfTheShowOnTheGridWithTheCurvesValuesExactly) {
  const Result r = sample({kSampledShow, "--rate", "4"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto rows = testing::csv_rows(r.out);
  const playback::Show show = config::load_show_file(kSampledShow);
  ASSERT_EQ(rows.size(), 1u + 12 * 4 + 1);  // header, then 0, 0.25, ..., 12 s
  ASSERT_EQ(rows[0].size(), 1 + show.tracks.size());
  EXPECT_EQ(rows[0][0], "seconds");
  for (std::size_t c = 0; c < show.tracks.size(); ++c) EXPECT_EQ(rows[0][c + 1], show.tracks[c].channel);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), rows[0].size()) << "row " << i;
    const double t = 0.25 * static_cast<double>(i - 1);
    EXPECT_EQ(std::strtod(rows[i][0].c_str(), nullptr), t);
    // Every number reads back to the very double the curve gives.
    for (std::size_t c = 0; c < show.tracks.size(); ++c)
      EXPECT_EQ(std::strtod(rows[i][c + 1].c_str(), nullptr), show.tracks[c].curve.evaluate(t))
          << show.tracks[c].channel << " at " << t << " s: " << rows[i][c + 1];
  }
}

TEST(SampleCommand, SamplesBeforeAndAfterTheKeysInTheOrderAsked) {
  const std::string path = testing::write_temp_file("small.yaml", kSmallShow);
  const Result r = sample({path, "--step", "0.25", "--from", "-0.5", "--to", "2.5", "--channels", "switch,ramp"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.out,
            "seconds,switch,ramp\n"
            "-0.5,1,0\n-0.25,1,0\n0,1,0\n0.25,1,0\n0.5,1,0\n0.75,1,2.5\n1,-2,5\n1.25,-2,7.5\n1.5,-2,10\n"
            "1.75,-2,10\n2,-2,10\n2.25,-2,10\n2.5,-2,10\n");
}

TEST(SampleCommand, PrintsGridTimesAsTheirShortDecimalAndIncludesTheEnd) {
  const std::string path = testing::write_temp_file("small.yaml", kSmallShow);
  const Result r = sample({path, "--step", "0.1", "--from", "-0.3", "--to", "0.3", "--channels", "ramp"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::vector<std::string> times;
  for (const auto& row : testing::csv_rows(r.out)) times.push_back(row[0]);
  EXPECT_EQ(times, (std::vector<std::string>{"seconds", "-0.3", "-0.2", "-0.1", "0", "0.1", "0.2", "0.3"}));
  // 1/3 s does not land on 2 s; the last row is the last grid time before it.
  const Result thirds = sample({path, "--rate", "3", "--to", "2", "--channels", "ramp"});
  ASSERT_EQ(thirds.code, kExitOk) << thirds.err;
  const auto rows = testing::csv_rows(thirds.out);
  ASSERT_EQ(rows.size(), 1u + 7);
  EXPECT_EQ(rows.back()[0], "2");
  const Result sevenths = sample({path, "--rate", "7", "--to", "0.5", "--channels", "ramp"});
  EXPECT_EQ(testing::csv_rows(sevenths.out).back()[0], "0.428571429");
}

TEST(SampleCommand, DefaultsToOneHundredHertzOverTheShow) {
  const std::string path = testing::write_temp_file("small.yaml", kSmallShow);
  const Result r = sample({path});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto rows = testing::csv_rows(r.out);
  ASSERT_EQ(rows.size(), 1u + 201);
  EXPECT_EQ(rows[1][0], "0");
  EXPECT_EQ(rows[2][0], "0.01");
  EXPECT_EQ(rows.back()[0], "2");
}

TEST(SampleCommand, WritesTheSameCsvToAFileWithOut) {
  const std::string path = testing::write_temp_file("small.yaml", kSmallShow);
  const std::string csv = testing::temp_path("out.csv");
  const Result to_file = sample({path, "--rate", "10", "--out", csv});
  ASSERT_EQ(to_file.code, kExitOk) << to_file.err;
  EXPECT_TRUE(to_file.out.empty());
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), sample({path, "--rate", "10"}).out);
}

TEST(SampleCommand, RefusesBadOptionsSayingWhatWasExpected) {
  const std::string path = testing::write_temp_file("small.yaml", kSmallShow);
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{path, "--channels", "ramp,jaw"}, "unknown channel 'jaw' in --channels; the show has: ramp, switch"},
      {{path, "--channels", "ramp,ramp"}, "channel 'ramp' is listed twice"},
      {{path, "--rate", "0"}, "expected --rate to be more than 0 Hz, found 0"},
      {{path, "--rate", "-5"}, "expected --rate to be more than 0 Hz, found -5"},
      {{path, "--step", "0"}, "expected --step to be more than 0 s, found 0"},
      {{path, "--rate", "10", "--step", "0.1"}, "--rate excludes --step"},
      {{path, "--from", "1", "--to", "1"}, "expected --from (1 s) to be before --to (1 s)"},
      {{path, "--from", "3"}, "expected --from (3 s) to be before --to (2 s), the show's duration"},
      {{path, "--to", "inf"}, "expected --to to be a finite number"},
      {{path, "--step", "1e-9"}, "expected samples at least 1e-06 s apart"},
      {{path, "--rate", "100000", "--to", "1000"}, "rows; expected at most 1e+07"},
      {{path, "--out", "/nonexistent-dir/x.csv"}, "cannot write --out /nonexistent-dir/x.csv"},
      {{testing::temp_path("missing.yaml")}, "missing.yaml"},
  };
  for (const auto& c : cases) {
    const Result r = sample(c.args);
    EXPECT_EQ(r.code, kExitBadInput) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(SampleCommand, RejectsABadShowWholeWithFileAndLine) {
  const std::string path = testing::write_temp_file("bad.yaml", "duration: 2\ntracks:\n  a:\n    - {time: 1, value: 0}\n    - {time: 0.5, value: 1}\n");
  const Result r = sample({path});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(path + ":5:"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(SampleCommand, TheBinaryWritesCsvToStandardOutputAndTeachesInItsHelp) {
  testing::ChildProcess run({AVAR_BINARY, "sample", kSampledShow, "--rate", "1", "--channels", "jaw"});
  ASSERT_TRUE(run.started());
  EXPECT_EQ(run.wait(), kExitOk) << run.err();
  const auto rows = testing::csv_rows(run.out());
  ASSERT_EQ(rows.size(), 1u + 13);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"seconds", "jaw"}));
  EXPECT_EQ(rows[8], (std::vector<std::string>{"7", "4"}));  // the jaw key at 7 s

  testing::ChildProcess help({AVAR_BINARY, "sample", "--help"});
  EXPECT_EQ(help.wait(), kExitOk);
  EXPECT_NE(help.out().find("Examples:"), std::string::npos) << help.out();
  EXPECT_NE(help.out().find("--channels"), std::string::npos) << help.out();
}

}  // namespace
}  // namespace avar::app

namespace avar::app {
namespace {

const std::string kSampledRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

// The device engine's CSV has the double engine's grid and columns, and every value within one
// 16-bit output unit of the double engine's over the rig channel's range.
TEST(SampleCommandDeviceEngine, MatchesTheDoubleEngineWithinOneOutputUnit) {
  const Result reference = sample({kSampledShow, "--rig", kSampledRig, "--rate", "50"});
  const Result device = sample({kSampledShow, "--rig", kSampledRig, "--rate", "50", "--engine", "device"});
  ASSERT_EQ(reference.code, kExitOk) << reference.err;
  ASSERT_EQ(device.code, kExitOk) << device.err;
  const auto a = testing::csv_rows(reference.out), b = testing::csv_rows(device.out);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a[0], b[0]);
  const rig::Rig rig = config::load_rig_file(kSampledRig);
  std::size_t compared = 0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    EXPECT_EQ(a[i][0], b[i][0]);
    for (std::size_t c = 1; c < a[0].size(); ++c) {
      const rig::ChannelSpec& channel = rig.channels[rig.find_channel(a[0][c]).value()];
      const double unit = (channel.max - channel.min) / 65535;
      EXPECT_LE(std::abs(std::strtod(a[i][c].c_str(), nullptr) - std::strtod(b[i][c].c_str(), nullptr)), 1.5 * unit)
          << a[0][c] << " at " << a[i][0] << " s";
      ++compared;
    }
  }
  EXPECT_GT(compared, 4000u);
}

TEST(SampleCommandDeviceEngine, NeedsTheRigAndRefusesALayeredShowSayingWhy) {
  const Result no_rig = sample({kSampledShow, "--engine", "device"});
  EXPECT_EQ(no_rig.code, kExitBadInput);
  EXPECT_NE(no_rig.err.find("--engine device needs --rig RIG"), std::string::npos) << no_rig.err;
  const Result layered =
      sample({AVAR_SOURCE_DIR "/examples/shows/layered-head.yaml", "--rig", kSampledRig, "--engine", "device"});
  EXPECT_EQ(layered.code, kExitBadInput);
  EXPECT_NE(layered.err.find("the device engine plays a show's tracks"), std::string::npos) << layered.err;
  const Result unknown = sample({kSampledShow, "--rig", kSampledRig, "--engine", "float"});
  EXPECT_NE(unknown.code, kExitOk);
}

}  // namespace
}  // namespace avar::app
