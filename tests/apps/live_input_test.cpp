// Live inputs end to end: OSC messages over loopback UDP into `avar play --sim`, `avar puppet`
// and `avar record`, checked on the trace the run writes.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <thread>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/osc_sender.hpp"
#include "../support/temp_file.hpp"
#include "avar/config/input_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"

namespace avar {
namespace {

const std::string kLiveRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml";

/// A trace as columns by name (empty cells as NaN).
struct LiveTrace {
  std::map<std::string, std::vector<double>> columns;
  std::vector<std::string> phase;

  explicit LiveTrace(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = testing::csv_cells(line);
    while (std::getline(in, line)) {
      std::vector<std::string> cells = testing::csv_cells(line);
      cells.resize(header.size());
      for (std::size_t i = 0; i < header.size(); ++i) {
        if (header[i] == "phase") {
          phase.push_back(cells[i]);
          continue;
        }
        columns[header[i]].push_back(cells[i].empty() ? std::nan("") : std::stod(cells[i]));
      }
    }
  }
  const std::vector<double>& at(const std::string& name) const {
    const auto it = columns.find(name);
    if (it == columns.end()) throw std::runtime_error("no column " + name);
    return it->second;
  }
};

/// Sends `value` to `path` every 20 ms from `from_s` to `to_s` after its start, on its own thread.
class TimedOscSender {
 public:
  TimedOscSender(int port, std::string path, double from_s, double to_s, std::function<float(double)> value)
      : thread_([=, this] {
          testing::OscSender osc(port);
          const auto start = std::chrono::steady_clock::now();
          for (;;) {
            const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (t > to_s || stop_) return;
            if (t >= from_s && osc.send(path, value(t))) ++sent_;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        }) {}
  ~TimedOscSender() {
    stop_ = true;
    thread_.join();
  }
  int sent() const { return sent_; }

 private:
  std::atomic<bool> stop_{false};
  std::atomic<int> sent_{0};
  std::thread thread_;
};

const char* kJawShow = R"(name: jaw-at-five
duration: 6
tracks:
  jaw:
    - {time: 0, value: 5}
    - {time: 6, value: 5}
)";

void expect_within_limits_and_speed(const LiveTrace& trace, double min, double max, double max_velocity,
                                    const std::string& channel) {
  const auto& s = trace.at("seconds");
  const auto& c = trace.at(channel + ".command");
  for (std::size_t k = 0; k < c.size(); ++k) {
    ASSERT_GE(c[k], min - 1e-9) << "tick " << k;
    ASSERT_LE(c[k], max + 1e-9) << "tick " << k;
    if (k > 0) {
      ASSERT_LE(std::abs(c[k] - c[k - 1]), max_velocity * (s[k] - s[k - 1]) * (1 + 1e-6) + 1e-9) << "tick " << k;
    }
  }
}

TEST(LiveInput, AnOscChannelMessageTakesTheJawOverAPlayingShowAndHandsItBack) {
  const int port = testing::free_udp_port();
  const std::string show = testing::write_temp_file("jaw-at-five.yaml", kJawShow);
  const std::string trace_path = testing::temp_path("live.csv");
  TimedOscSender sender(port, "/avar/channel/jaw", 0.0, 2.5, [](double) { return 20.0f; });
  const testing::CliResult r = testing::run_avar({"play", show, "--rig", kLiveRig, "--sim", "--no-progress", "--priority", "0",
                                                  "--input", "osc://127.0.0.1:" + std::to_string(port), "--trace", trace_path});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("input OSC"), std::string::npos) << r.out;
  const LiveTrace trace(trace_path);
  const auto& jaw = trace.at("jaw.command");
  const auto& sent = trace.at("input.channel/jaw");
  bool took = false, heard = false;
  for (std::size_t k = 0; k < jaw.size(); ++k) {
    took = took || (trace.phase[k] == "running" && std::abs(jaw[k] - 20) < 1e-6);
    heard = heard || sent[k] == 20;
  }
  EXPECT_TRUE(heard);
  EXPECT_TRUE(took) << "the jaw never reached the value sent over OSC";
  // 2 s after the last message the direct layer hands back; the show holds 5 at its end.
  std::size_t last_running = 0;
  for (std::size_t k = 0; k < jaw.size(); ++k)
    if (trace.phase[k] == "running") last_running = k;
  EXPECT_NEAR(jaw[last_running], 5, 1e-6);
  expect_within_limits_and_speed(trace, 0, 30, 300, "jaw");
}

TEST(LiveInput, PuppetMovesAChannelThroughAMappedControlAndEndsAfterItsDuration) {
  const int port = testing::free_udp_port();
  const std::string inputs = testing::write_temp_file(
      "puppet-inputs.yaml", "inputs:\n  mappings:\n    - {control: look, channel: neck_pan, range: [-50, 50], crossfade: 0.1}\n");
  const std::string trace_path = testing::temp_path("puppet.csv");
  // 0.75 on a unipolar control spans [-50, 50] at 25.
  TimedOscSender sender(port, "/avar/control/look", 0.0, 1.5, [](double) { return 0.75f; });
  const testing::CliResult r =
      testing::run_avar({"puppet", "--rig", kLiveRig, "--sim", "--no-progress", "--priority", "0", "--input",
                         "osc://:" + std::to_string(port), "--inputs", inputs, "--duration", "2", "--trace", trace_path});
  ASSERT_EQ(r.code, 0) << r.err;
  const LiveTrace trace(trace_path);
  const auto& pan = trace.at("neck_pan.command");
  double peak = 0;
  for (std::size_t k = 0; k < pan.size(); ++k)
    if (trace.phase[k] == "running") peak = std::max(peak, pan[k]);
  EXPECT_NEAR(peak, 25, 1e-6);
  EXPECT_NEAR(pan.back(), 0, 1e-6);  // eased back to rest at the end
  expect_within_limits_and_speed(trace, -60, 60, 180, "neck_pan");
}

TEST(LiveInput, ARecordedTakePlaysBackWithinItsTolerance) {
  const int port = testing::free_udp_port();
  const std::string take = testing::temp_path("take.yaml");
  const std::string trace_path = testing::temp_path("record.csv");
  TimedOscSender sender(port, "/avar/channel/jaw", 0.0, 2.2,
                        [](double t) { return static_cast<float>(15 + 10 * std::sin(2 * 3.14159265 * 0.8 * t)); });
  const testing::CliResult r = testing::run_avar({"record", "--rig", kLiveRig, "--sim", "--no-progress", "--priority", "0",
                                                  "--input", "osc://127.0.0.1:" + std::to_string(port), "--duration", "2.5",
                                                  "--tolerance", "0.2", "--out", take, "--trace", trace_path});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("jaw: "), std::string::npos) << r.out;
  const playback::Show written = config::load_show_file(take);
  ASSERT_EQ(written.tracks.size(), 1u);  // only the channel a control moved
  EXPECT_EQ(written.tracks[0].channel, "jaw");
  const LiveTrace trace(trace_path);
  const auto& s = trace.at("seconds");
  const auto& jaw = trace.at("jaw.command");
  double start = -1;
  playback::CurveCursor cursor;
  std::size_t checked = 0;
  for (std::size_t k = 0; k < jaw.size(); ++k) {
    if (trace.phase[k] != "running") continue;
    if (start < 0) start = s[k];
    EXPECT_NEAR(written.tracks[0].curve.evaluate(s[k] - start, cursor), jaw[k], 0.2 + 1e-6) << "tick " << k;
    ++checked;
  }
  EXPECT_GT(checked, 50u);
}

TEST(LiveInput, AMergedTakeLiesOnItsOwnLayerOverACopyOfTheShow) {
  const int port = testing::free_udp_port();
  const std::string show = testing::write_temp_file("merge-show.yaml", R"(name: short
duration: 2
tracks:
  jaw:
    - {time: 0, value: 5}
    - {time: 2, value: 5}
  neck_pan:
    - {time: 0, value: 0}
    - {time: 2, value: 20}
)");
  const std::string take = testing::temp_path("merged.yaml");
  TimedOscSender sender(port, "/avar/channel/jaw", 0.0, 2.5, [](double) { return 15.0f; });
  const testing::CliResult r =
      testing::run_avar({"record", "--rig", kLiveRig, "--show", show, "--merge", "--sim", "--no-progress", "--priority", "0",
                         "--input", "osc://127.0.0.1:" + std::to_string(port), "--out", take});
  ASSERT_EQ(r.code, 0) << r.err;
  const playback::Show merged = config::load_show_file(take);
  EXPECT_EQ(merged.tracks.size(), 2u);  // the show's own tracks, kept
  ASSERT_EQ(merged.layers.size(), 1u);
  EXPECT_EQ(merged.layers[0].name, "take");
  ASSERT_EQ(merged.clips.size(), 1u);
  ASSERT_EQ(merged.clips[0].tracks.size(), 1u);  // only the performed channel
  EXPECT_EQ(merged.clips[0].tracks[0].channel, "jaw");
  playback::CurveCursor cursor;
  EXPECT_NEAR(merged.clips[0].tracks[0].curve.evaluate(1.5, cursor), 15, 0.25 + 1e-6);
}

TEST(LiveInput, LearnMapsEachChannelToTheControlMovedForIt) {
  const int port = testing::free_udp_port();
  const std::string out = testing::temp_path("learned.yaml");
  // A jittering control first (never half its range), then the fader meant for the jaw, then
  // the one for neck_pan.
  TimedOscSender jitter(port, "/avar/control/noise", 0.0, 3.0,
                        [](double t) { return static_cast<float>(0.5 + 0.1 * std::sin(20 * t)); });
  TimedOscSender jaw(port, "/avar/control/fader1", 0.6, 1.2, [](double t) { return static_cast<float>((t - 0.6) / 0.6); });
  TimedOscSender pan(port, "/avar/control/knob7", 1.8, 2.6, [](double t) { return static_cast<float>((t - 1.8) / 0.8); });
  const testing::CliResult r =
      testing::run_avar({"inputs", "learn", "--rig", kLiveRig, "--input", "osc://127.0.0.1:" + std::to_string(port), "--channels",
                         "jaw,neck_pan", "--out", out, "--timeout", "10"});
  ASSERT_EQ(r.code, 0) << r.err;
  const rig::Rig rig = config::load_rig_file(kLiveRig);
  const config::InputMap map = config::load_input_map(rig, out, true);
  ASSERT_EQ(map.mappings.size(), 2u);
  EXPECT_EQ(map.mappings[0].control, "fader1");
  EXPECT_EQ(map.mappings[0].channel, 0u);
  EXPECT_EQ(map.mappings[1].control, "knob7");
  EXPECT_EQ(map.devices, std::vector<std::string>{"osc://127.0.0.1:" + std::to_string(port)});
}

TEST(LiveInput, RefusesMissingOrUnreadableInputsBeforeAnythingMoves) {
  testing::CliResult r = testing::run_avar({"puppet", "--rig", kLiveRig, "--sim"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no input device"), std::string::npos) << r.err;
  r = testing::run_avar({"puppet", "--rig", kLiveRig, "--sim", "--input", "carrier-pigeon:7"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("osc://"), std::string::npos) << r.err;  // the accepted forms are taught
  r = testing::run_avar({"play", std::string(AVAR_SOURCE_DIR) + "/examples/shows/hello-head.yaml", "--rig", kLiveRig, "--fast",
                         "--input", "osc://:9000"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("drop --fast"), std::string::npos) << r.err;
}

TEST(LiveInput, ARecordingWithNoControlMappedToAChannelIsRefusedBeforeAnythingMoves) {
  // The haunt prop with a button of the control role but no inputs: mappings: nothing could be
  // performed, so nothing may run.
  std::ifstream in(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/haunt-prop.yaml");
  std::stringstream rig;
  rig << in.rdbuf() << "  button: {chip: sim, line: 6, active_low: true, bias: pull_up, role: control}\n";
  const std::string rig_path = testing::write_temp_file("control-rig.yaml", rig.str());
  const std::string take = testing::temp_path("no-take.yaml");
  const testing::CliResult r = testing::run_avar(
      {"record", "--rig", rig_path, "--sim", "--no-progress", "--priority", "0", "--duration", "1", "--out", take});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("nothing to record: no live control reaches a channel"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("playing"), std::string::npos) << r.err;  // refused before the run
  EXPECT_FALSE(std::ifstream(take).good());
}

}  // namespace
}  // namespace avar
