// `avar play` and `avar check` run in-process, as a user runs them: exit codes, messages, and
// that nothing reaches a device when the input is bad.
#include <sys/file.h>

#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/temp_file.hpp"
#include "avar/cli.hpp"
#include "avar/exit_codes.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/sim_maestro.hpp"

namespace avar::app {
namespace {

const std::string kHelloRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";
const std::string kHelloShow = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";

using Result = testing::CliResult;
Result avar(std::vector<std::string> args) { return testing::run_avar(std::move(args)); }

std::string write_temp(const std::string& name, const std::string& text) { return testing::write_temp_file(name, text); }

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string bundled_show_with(const std::string& from, const std::string& to) {
  std::string text = read_file(kHelloShow);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(PlayCommand, PlaysTheBundledShowOnTheSimulatorAndSummarises) {
  const std::string trace = testing::temp_path("trace.csv");
  const std::string plot = testing::temp_path("plot.svg");
  const Result r = avar({"play", kHelloShow, "--rig", kHelloRig, "--fast", "--trace", trace, "--plot", plot});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  for (const char* channel : {"jaw", "neck_pan", "neck_tilt", "neck_roll", "eyes_pan", "eyes_tilt", "lid_left", "lid_right"})
    EXPECT_NE(r.out.find(channel), std::string::npos) << channel;
  EXPECT_NE(r.out.find("max err"), std::string::npos);
  EXPECT_NE(r.out.find("deadline misses 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("simulated Maestro"), std::string::npos) << r.out;

  // The trace's last row: the figure is back at rest, commanded and (nearly) simulated.
  std::ifstream csv(trace);
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("seconds,phase,wake_late_us,sample_us,ik_us,mix_us,limit_us,send_us,jaw.target,jaw.command,jaw.measured,"
                         "neck_pan.target",
                         0),
            0u)
      << header;
  int rows = 0;
  while (std::getline(csv, line)) {
    last = line;
    ++rows;
  }
  EXPECT_GT(rows, 12 * 50);  // 12 s show at 50 Hz, plus soft start and stop
  std::vector<std::string> cells;
  std::stringstream cells_in(last);
  for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
  ASSERT_EQ(cells.size(), 8u + 8u * 3u);
  EXPECT_DOUBLE_EQ(std::stod(cells[9]), 0.0);               // jaw command = rest
  EXPECT_NEAR(std::stod(cells[10]), 0.0, 0.5);              // jaw simulated position
  EXPECT_DOUBLE_EQ(std::stod(cells[8 + 6 * 3 + 1]), 20.0);  // lid_left command = rest 20 %
  EXPECT_NE(read_file(plot).find("<svg"), std::string::npos);
}

TEST(PlayCommand, PlaysTheDynamixelArmOnTheSimulatedBusAndReportsTheWire) {
  const std::string trace = testing::temp_path("trace.csv");
  const Result r = avar({"play", AVAR_SOURCE_DIR "/examples/shows/arm-wave.yaml", "--rig",
                         AVAR_SOURCE_DIR "/examples/rigs/dynamixel-arm.yaml", "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("simulated DYNAMIXEL 2.0 (4 servos)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 0 CRC errors, 0 framing errors, 0 timeouts"), std::string::npos) << r.out;  // simulated links wait long enough
  for (const char* channel : {"base", "shoulder", "elbow", "wrist"}) EXPECT_NE(r.out.find(channel), std::string::npos);
  // The trace carries what the servos reported and the wire's counters, tick by tick.
  std::ifstream csv(trace);
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_NE(header.find(",wrist.measured,wrist.load,wrist.temperature_c,wrist.device_faults"), std::string::npos) << header;
  EXPECT_NE(header.find(",arm.replies,arm.crc_errors,arm.framing_errors,arm.timeouts,arm.retries,arm.reconnects"), std::string::npos);
  while (std::getline(csv, line)) last = line;
  std::vector<std::string> names, cells;
  std::stringstream h(header), l(last);
  for (std::string cell; std::getline(h, cell, ',');) names.push_back(cell);
  for (std::string cell; std::getline(l, cell, ',');) cells.push_back(cell);
  ASSERT_EQ(names.size(), cells.size());
  const auto at = [&](const std::string& name) { return cells[static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin())]; };
  EXPECT_NEAR(std::stod(at("base.temperature_c")), 25, 3);
  EXPECT_EQ(at("base.device_faults"), "0");
  EXPECT_GT(std::stoul(at("arm.replies")), 3000u);
}

TEST(PlayCommand, PlaysTheBundledShowThroughAnSsc32) {
  // The hello-head figure rewired to a Lynxmotion SSC-32: same channels, same pulse windows.
  std::string rig = read_file(kHelloRig);
  rig.replace(rig.find("maestro: {model: mini12}"), 24, "ssc32: {}");
  for (std::string::size_type at; (at = rig.find("protocol: maestro, ")) != std::string::npos;) rig.erase(at, 19);
  const std::string path = write_temp("ssc32-head.yaml", rig);
  const Result r = avar({"play", kHelloShow, "--rig", path, "--fast", "--no-progress"});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("simulated SSC-32"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("jaw "), std::string::npos);
}

TEST(PlayCommand, PlaysTheFeetechArmOnTheSimulatedBus) {
  const Result r = avar({"play", AVAR_SOURCE_DIR "/examples/shows/arm-wave.yaml", "--rig",
                         AVAR_SOURCE_DIR "/examples/rigs/feetech-arm.yaml", "--fast", "--no-progress"});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("simulated Feetech STS bus (IDs 1,2,3,4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 0 CRC errors, 0 framing errors, 0 timeouts"), std::string::npos) << r.out;
}

TEST(PlayCommand, PlaysAMixedMaestroDynamixelAndDmxFigureInOneShow) {
  const std::string trace = testing::temp_path("trace.csv");
  const Result r = avar({"play", AVAR_SOURCE_DIR "/examples/shows/mixed-figure.yaml", "--rig",
                         AVAR_SOURCE_DIR "/examples/rigs/mixed-figure.yaml", "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("link head: simulated Maestro"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("link arm: simulated DYNAMIXEL 2.0 (2 servos)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("link lights: simulated DMX USB Pro"), std::string::npos) << r.out;
  // Mid-show (about 5 s into the show: the arm raised into the lit spot), every bus carried its
  // part: each simulated device is where its channel was commanded.
  std::ifstream csv(trace);
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> names;
  std::stringstream header_in(header);
  for (std::string cell; std::getline(header_in, cell, ',');) names.push_back(cell);
  auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  bool seen = false;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    if (std::stod(cells[0]) < 5.3) continue;
    const auto value = [&](const std::string& name) { return std::stod(cells[column(name)]); };
    EXPECT_GT(value("shoulder.command"), 20);                                      // raised
    EXPECT_NEAR(value("shoulder.measured"), value("shoulder.command"), 2);         // DYNAMIXEL servo
    EXPECT_NEAR(value("spot.measured"), 100, 0.5);                                 // DMX level, 16 bit
    EXPECT_NEAR(value("neck_pan.measured"), value("neck_pan.command"), 1);         // Maestro servo
    seen = true;
    break;
  }
  EXPECT_TRUE(seen);
}

TEST(PlayCommand, PlaysATargetThroughInverseKinematics) {
  const std::string trace = testing::temp_path("trace.csv");
  const Result r = avar({"play", AVAR_SOURCE_DIR "/examples/shows/look-around.yaml", "--rig",
                         AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml", "--fast", "--no-progress", "--trace", trace});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.out.find("0 degraded (target out of reach: closest pose used), 0 failed"), std::string::npos) << r.out;
  // The head turned both ways and looked up, following the target.
  std::ifstream csv(trace);
  std::string header, line;
  std::getline(csv, header);
  EXPECT_NE(header.find("ik_us"), std::string::npos);
  double pan_lo = 0, pan_hi = 0, tilt_hi = 0;
  while (std::getline(csv, line)) {
    std::vector<double> cells;
    std::stringstream in(line);
    std::string cell;
    for (int i = 0; std::getline(in, cell, ','); ++i)
      cells.push_back(i == 1 || cell.empty() ? 0.0 : std::stod(cell));
    pan_lo = std::min(pan_lo, cells[8]);  // neck_pan.command
    pan_hi = std::max(pan_hi, cells[8]);
    tilt_hi = std::max(tilt_hi, cells[11]);  // neck_tilt.command
  }
  EXPECT_LT(pan_lo, -30);
  EXPECT_GT(pan_hi, 30);
  EXPECT_GT(tilt_hi, 15);
}

TEST(PlayCommand, FastRunsAreDeterministic) {
  const std::string a = testing::temp_path("a.csv");
  const std::string b = testing::temp_path("b.csv");
  ASSERT_EQ(avar({"play", kHelloShow, "--rig", kHelloRig, "--fast", "--trace", a}).code, kExitOk);
  ASSERT_EQ(avar({"play", kHelloShow, "--rig", kHelloRig, "--fast", "--trace", b}).code, kExitOk);
  EXPECT_EQ(read_file(a), read_file(b));
}

TEST(CheckCommand, ListsWhatTheRigCannotDoAndRetimes) {
  const std::string fast_show = write_temp("fast.yaml", "duration: 4\ntracks:\n  jaw:\n    - {time: 0, value: 0}\n"
                                                         "    - {time: 0.05, value: 30}\n    - {time: 4, value: 0}\n");
  const std::string out = testing::temp_path("retimed.yaml");
  const Result r = avar({"check", fast_show, "--rig", kHelloRig, "--retime", out});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("infeasible: " + fast_show + ":4:7: jaw 0-0.05 s: speed 600 deg/s, allowed 300 deg/s"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("retimed show: " + out), std::string::npos) << r.out;
  const Result again = avar({"check", out, "--rig", kHelloRig});
  EXPECT_EQ(again.code, kExitOk);
  EXPECT_NE(again.out.find("0 segment(s) ask more"), std::string::npos) << again.out;
}

TEST(CheckCommand, AcceptsTheBundledShow) {
  const Result r = avar({"check", kHelloShow, "--rig", kHelloRig});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("ok: show 'hello-head'"), std::string::npos) << r.out;
}

/// A simulated Maestro on a pty that a bad-input run is pointed at: it must receive nothing.
struct WatchedPort {
  sim::SimMaestro device{sim::SimMaestroConfig{}};
  sim::PtyDeviceHost host{device, sim::PtyDeviceHost::Clock::stepped};
  std::uint64_t bytes() { return host.with_device([&](auto&) { return device.bytes_received(); }); }
};

void expect_rejected(const std::string& show_text, const std::string& expected_message) {
  WatchedPort port;
  const std::string show = write_temp("bad-show.yaml", show_text);
  const Result r = avar({"play", show, "--rig", kHelloRig, "--port", port.host.slave_path()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(expected_message), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("error: " + show + ":"), std::string::npos) << "the message must start with the file: " << r.err;
  EXPECT_EQ(port.bytes(), 0u) << "bytes reached the device before validation finished";
}

TEST(PlayCommand, KeysNotStrictlyIncreasingAreRejectedBeforeAnythingIsSent) {
  expect_rejected(bundled_show_with("{time: 4.08, value: 5}", "{time: 3.5, value: 5}"), "strictly increase");
}

TEST(PlayCommand, ValuesOutsideTheChannelLimitsAreRejectedBeforeAnythingIsSent) {
  expect_rejected(bundled_show_with("{time: 7.2, value: 22}", "{time: 7.2, value: 44}"),
                  "value 44 at 7.2 s is outside channel 'jaw' limits [0, 30] deg");
}

TEST(PlayCommand, UnknownChannelsAreRejectedBeforeAnythingIsSent) {
  expect_rejected(bundled_show_with("  jaw:\n", "  chin:\n"), "unknown channel 'chin'");
}

TEST(PlayCommand, MalformedYamlIsRejectedBeforeAnythingIsSent) {
  expect_rejected(bundled_show_with("{time: 7.2, value: 22}", "{time: 7.2, value: 22"), "malformed YAML");
}

TEST(PlayCommand, UnknownInterpolationIsRejectedBeforeAnythingIsSent) {
  expect_rejected(bundled_show_with("{time: 6.8, value: 18}", "{time: 6.8, value: 18, interpolation: cubical}"),
                  "interpolation");
}

TEST(PlayCommand, BadRigIsRejectedWithItsLocation) {
  std::string rig = read_file(kHelloRig);
  rig.replace(rig.find("protocol: maestro"), 17, "protocol: maestr0");
  const std::string path = write_temp("bad-rig.yaml", rig);
  const Result r = avar({"play", kHelloShow, "--rig", path, "--fast"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(path + ":25:36: unknown protocol 'maestr0'; expected one of: maestro"), std::string::npos) << r.err;
}

TEST(PlayCommand, MissingPortIsNamed) {
  const Result r = avar({"play", kHelloShow, "--rig", kHelloRig, "--port", "/dev/ttyACM_avar_absent"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("/dev/ttyACM_avar_absent: cannot open serial port"), std::string::npos) << r.err;
}

TEST(PlayCommand, BusyPortIsRefused) {
  WatchedPort port;
  const std::string path = port.host.slave_path();
  // Another program holds the port (and its lock).
  std::FILE* other = std::fopen(path.c_str(), "r+");
  ASSERT_NE(other, nullptr);
  ASSERT_EQ(::flock(::fileno(other), LOCK_EX | LOCK_NB), 0);
  const Result r = avar({"play", kHelloShow, "--rig", kHelloRig, "--port", path});
  std::fclose(other);
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find(path + ": serial port is busy"), std::string::npos) << r.err;
  EXPECT_EQ(port.bytes(), 0u);
}

TEST(PlayCommand, FastNeedsTheSimulator) {
  WatchedPort port;
  const Result r = avar({"play", kHelloShow, "--rig", kHelloRig, "--port", port.host.slave_path(), "--fast"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--fast runs on a simulated clock"), std::string::npos) << r.err;
  EXPECT_EQ(port.bytes(), 0u);
}

TEST(Cli, HelpTeachesAndBadOptionsExitWithTwo) {
  const Result help = avar({"--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
  EXPECT_EQ(avar({"play", kHelloShow}).code, kExitBadInput);  // --rig is required
  EXPECT_EQ(avar({"play", kHelloShow, "--rig", kHelloRig, "--rate", "5000"}).code, kExitBadInput);
  EXPECT_EQ(avar({"play", kHelloShow, "--rig", kHelloRig, "--fast", "--realtime"}).code, kExitBadInput);
}

}  // namespace
}  // namespace avar::app
