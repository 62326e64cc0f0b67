// `avar fit`: end to end (sample a bundled show, fit it, sample the fitted show: every value
// within the tolerance), noisy recordings with smoothing, and the refusals of bad CSV input with
// file, line and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

using Result = testing::CliResult;
using testing::run_avar;

std::vector<std::vector<double>> numbers_of(const std::string& path, std::string& header) {
  std::ifstream file(path);
  std::getline(file, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(file, line);) {
    std::vector<double> row;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(FitCommand, BundledShowRoundTripsWithinToleranceWithFewerKeys) {
  const std::string samples = testing::temp_path("in.csv"), fitted = testing::temp_path("fit.yaml"),
                    resampled = testing::temp_path("out.csv");
  ASSERT_EQ(run_avar({"sample", AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml", "--rate", "100", "--out", samples}).code, kExitOk);
  const double tolerance = 0.05;
  const Result fit = run_avar({"fit", samples, "--tolerance", "0.05", "--out", fitted});
  ASSERT_EQ(fit.code, kExitOk) << fit.err;
  EXPECT_NE(fit.out.find("jaw: 1201 samples in, "), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("wrote " + fitted), std::string::npos) << fit.out;
  // The written show loads with the show loader, and every track has far fewer keys than samples.
  const playback::Show show = config::load_show_file(fitted);
  EXPECT_EQ(show.duration, 12.0);
  for (const auto& track : show.tracks) EXPECT_LT(track.curve.key_count() * 5, 1201u) << track.channel;
  ASSERT_EQ(run_avar({"sample", fitted, "--rate", "100", "--out", resampled}).code, kExitOk);
  std::string header_in, header_out;
  const auto in = numbers_of(samples, header_in), out = numbers_of(resampled, header_out);
  EXPECT_EQ(header_in, header_out);
  ASSERT_EQ(in.size(), out.size());
  for (std::size_t r = 0; r < in.size(); ++r) {
    ASSERT_EQ(in[r].size(), out[r].size());
    EXPECT_EQ(in[r][0], out[r][0]);
    for (std::size_t c = 1; c < in[r].size(); ++c) ASSERT_LE(std::abs(in[r][c] - out[r][c]), tolerance) << "row " << r << " column " << c;
  }
}

TEST(FitCommand, NoisyRecordingWithEverySmoothingMethod) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.3);
  std::ostringstream csv;
  csv << "seconds,pan,tilt\n";
  for (int i = 0; i <= 1000; ++i) {
    const double t = i / 100.0;
    csv << t << ',' << 20 * std::sin(0.7 * t) + noise(rng) << ',' << 5 * std::cos(1.3 * t) + 3 + noise(rng) << '\n';
  }
  const std::string path = testing::write_temp_file("noisy.csv", csv.str()), fitted = testing::temp_path("noisy.yaml");
  for (const char* method : {"none", "moving_average", "gaussian", "bspline", "butterworth"}) {
    const Result fit = run_avar({"fit", path, "--tolerance", "1.5", "--out", fitted, "--smooth", method, "--cutoff", "3"});
    ASSERT_EQ(fit.code, kExitOk) << method << ": " << fit.err;
    const playback::Show show = config::load_show_file(fitted);
    ASSERT_EQ(show.tracks.size(), 2u);
    for (const auto& track : show.tracks) EXPECT_LT(track.curve.key_count() * 10, 1001u) << method << " " << track.channel;
    if (std::string(method) != "none") {
      EXPECT_NE(fit.out.find("against the input"), std::string::npos) << fit.out;
    }
  }
}

TEST(FitCommand, StepIsKept) {
  const std::string path = testing::write_temp_file("step.csv", "seconds,switch\n0,0\n0.1,0\n0.2,0\n0.3,5\n0.4,5\n0.5,5\n");
  const std::string fitted = testing::temp_path("step.yaml");
  ASSERT_EQ(run_avar({"fit", path, "--tolerance", "0.01", "--out", fitted}).code, kExitOk);
  const playback::Show show = config::load_show_file(fitted);
  EXPECT_EQ(show.tracks[0].curve.key_count(), 4u);
  EXPECT_NEAR(show.tracks[0].curve.evaluate(0.2), 0, 1e-12);
  EXPECT_NEAR(show.tracks[0].curve.evaluate(0.3), 5, 1e-12);
}

/// Runs fit on `csv` and returns the error line.
std::string refusal(const std::string& name, const std::string& csv, std::vector<std::string> extra = {}) {
  const std::string path = testing::write_temp_file(name, csv);
  std::vector<std::string> args = {"fit", path, "--tolerance", "0.1", "--out", testing::temp_path("never.yaml")};
  args.insert(args.end(), extra.begin(), extra.end());
  const Result r = run_avar(args);
  EXPECT_EQ(r.code, kExitBadInput) << csv;
  EXPECT_TRUE(r.out.empty()) << r.out;
  return r.err;
}

TEST(FitCommand, BadCsvIsRefusedWithFileLineAndWhatWasExpected) {
  EXPECT_NE(refusal("empty.csv", "").find("empty.csv:1:1: the file is empty; expected a header"), std::string::npos);
  EXPECT_NE(refusal("no-seconds.csv", "time,jaw\n0,1\n").find("no-seconds.csv:1:1: found 'time' as the first column; expected the header to start with 'seconds'"),
            std::string::npos);
  EXPECT_NE(refusal("no-channel.csv", "seconds\n0\n").find(":1:1: found only 'seconds' in the header; expected at least one channel"),
            std::string::npos);
  EXPECT_NE(refusal("twice.csv", "seconds,a,a\n0,1,1\n").find(":1:11: channel 'a' appears twice"), std::string::npos);
  EXPECT_NE(refusal("rows.csv", "seconds,jaw\n").find("rows.csv:1:1: found no rows after the header"), std::string::npos);
  EXPECT_NE(refusal("backwards.csv", "seconds,jaw\n0,1\n0.5,2\n0.4,3\n")
                .find("backwards.csv:4:1: time 0.4 s is not after the previous row's 0.5 s; expected times to strictly increase"),
            std::string::npos);
  EXPECT_NE(refusal("nan.csv", "seconds,jaw,pan\n0,1,2\n1,nan,3\n").find("nan.csv:3:3: found nan in column 'jaw'; expected a finite number"),
            std::string::npos);
  EXPECT_NE(refusal("text.csv", "seconds,jaw\n0,1\n1,abc\n").find("text.csv:3:3: found 'abc' in column 'jaw'; expected a number"),
            std::string::npos);
  EXPECT_NE(refusal("ragged.csv", "seconds,jaw,pan\n0,1,2\n1,2\n").find("ragged.csv:3:1: found 2 cells; expected 3"), std::string::npos);
  EXPECT_NE(refusal("negative.csv", "seconds,jaw\n-1,1\n0,2\n").find("negative.csv:2:1: found time -1 s; expected times of 0 s or more"),
            std::string::npos);
  EXPECT_NE(refusal("zero.csv", "seconds,jaw\n0,1\n").find("zero.csv:2:1: the samples end at 0 s"), std::string::npos);
  EXPECT_NE(refusal("uneven.csv", "seconds,jaw\n0,1\n0.1,2\n0.3,3\n", {"--smooth", "gaussian", "--cutoff", "1"})
                .find("uneven.csv:3:1: samples 0.1 s apart where the mean spacing is 0.15 s; expected evenly spaced"),
            std::string::npos);
  EXPECT_NE(refusal("cutoff.csv", "seconds,jaw\n0,1\n1,2\n", {"--smooth", "gaussian"}).find("error: --smooth: gaussian needs --cutoff HZ"),
            std::string::npos);
  EXPECT_NE(refusal("nyquist.csv", "seconds,jaw\n0,1\n0.1,2\n0.2,1\n", {"--smooth", "butterworth", "--cutoff", "5"})
                .find("error: --cutoff: expected below half the sample rate (5 Hz), found 5 Hz"),
            std::string::npos);
  EXPECT_NE(refusal("missing.csv", "seconds,jaw\n0,1\n").find("missing.csv"), std::string::npos);
  const Result missing = run_avar({"fit", "/nonexistent/x.csv", "--tolerance", "1", "--out", testing::temp_path("x.yaml")});
  EXPECT_EQ(missing.code, kExitBadInput);
  EXPECT_NE(missing.err.find("/nonexistent/x.csv: cannot open the file"), std::string::npos) << missing.err;
  EXPECT_EQ(run_avar({"fit", "a.csv", "--tolerance", "0", "--out", "b.yaml"}).code, kExitBadInput);
}

TEST(FitCommand, HelpHasExamples) {
  const Result help = run_avar({"fit", "--help"});
  EXPECT_EQ(help.code, kExitOk);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
  EXPECT_NE(help.out.find("--smooth"), std::string::npos);
}

}  // namespace
}  // namespace avar::app
