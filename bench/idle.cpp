// avar-bench-idle: what idle life and behaviour layers cost per tick, each with its peer.
//  - Look-at gaze: one IdleLayer::apply on the gaze-eyes rig (blinks, breathing, gaze whose eyes
//    are aimed by IK every tick). Peer: the same rig and idle section with the eyes moved by
//    per-eye channel offsets (vergence as an angle), no IK.
//  - Behaviour layers: one control tick of hello-head playing lively-head (two behaviour layers
//    and a clip layer). Peer: the same tick playing layered-head (clip layers only).
// Each prints median and worst over every call, measured one by one.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/discard_transport.hpp"
#include "avar/assembly/maestro_protocol.hpp"
#include "avar/config/idle_section.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/idle_layer.hpp"
#include "avar/firmware_iface/maestro_link.hpp"

namespace {

class IdleBenchTimes {
 public:
  IdleBenchTimes() { ns_.reserve(1 << 21); }
  template <class F>
  void time(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    const auto t1 = std::chrono::steady_clock::now();
    if (ns_.size() < ns_.capacity()) ns_.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
  }
  void report(benchmark::State& state, const char* what) {
    std::sort(ns_.begin(), ns_.end());
    const auto at = [&](double f) {
      return ns_.empty() ? 0.0 : ns_[static_cast<std::size_t>(f * static_cast<double>(ns_.size() - 1))];
    };
    state.counters["median_ns"] = at(0.5);
    state.counters["worst_ns"] = at(1.0);
    std::printf("idle,case=%s,calls=%zu,median_us=%.3f,p99_us=%.3f,worst_us=%.3f\n", what, ns_.size(), at(0.5) / 1000.0,
                at(0.99) / 1000.0, at(1.0) / 1000.0);
  }

 private:
  std::vector<double> ns_;
};

std::string idle_bench_read(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// gaze-eyes.yaml, or the same rig with its gaze on per-eye channel offsets (no IK).
std::string idle_bench_rig(bool look_at) {
  std::string source = AVAR_SOURCE_DIR "/examples/rigs/gaze-eyes.yaml";
  if (look_at) return source;
  std::string text = idle_bench_read(source);
  const auto replace_line = [&](const std::string& start, const std::string& with) {
    const auto a = text.find(start);
    text.replace(a, text.find('\n', a) - a, with);
  };
  replace_line("    look_at:", "    eyes: {left_pan: eye_l_pan, right_pan: eye_r_pan, tilt: eyes_tilt}");
  replace_line("    distance:", "    near: {probability: 0.25, distance_m: 0.3}");
  const auto path = std::filesystem::temp_directory_path() / "avar-bench-idle-offsets.yaml";
  std::ofstream(path) << text;
  return path.string();
}

void idle_bench_gaze(benchmark::State& state, bool look_at) {
  const std::string path = idle_bench_rig(look_at);
  const avar::rig::Rig rig = avar::config::load_rig_file(path);
  const avar::playback::IdleSpec spec = *avar::config::load_idle_section(rig, path);
  avar::control::IdleLayer idle(spec, 7, std::vector<char>(rig.channels.size(), 0), rig.kinematics ? &*rig.kinematics : nullptr);
  std::vector<double> frame = rig.rest_frame();
  IdleBenchTimes times;
  std::uint64_t k = 0;
  for (auto _ : state) {
    const double now = static_cast<double>(k++) / 1000.0;
    times.time([&] { idle.apply(now, frame); });
    benchmark::DoNotOptimize(frame.data());
  }
  times.report(state, look_at ? "look_at_gaze_1khz" : "peer_offset_gaze_1khz");
}
void BM_IdleLookAtGaze(benchmark::State& state) { idle_bench_gaze(state, true); }
void BM_IdleOffsetGaze(benchmark::State& state) { idle_bench_gaze(state, false); }
BENCHMARK(BM_IdleLookAtGaze)->Iterations(120000);
BENCHMARK(BM_IdleOffsetGaze)->Iterations(120000);

void idle_bench_show(benchmark::State& state, const char* show_name) {
  const avar::rig::Rig rig = avar::config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  avar::playback::Show show = avar::config::load_show_file(std::string(AVAR_SOURCE_DIR "/examples/shows/") + show_name + ".yaml");
  avar::config::bind_show_behaviour(show, rig);
  show.loop = true;  // as many ticks as the benchmark wants (each wrap restarts the behaviour)
  avar::testing::DiscardTransport transport;
  avar::firmware_iface::MaestroLink link{transport, avar::assembly::maestro_config(rig, 0)};
  avar::control::Controller controller(rig, show, {&link}, {.tick_period_s = 0.001});
  controller.begin(0.0, rig.rest_frame());
  IdleBenchTimes times;
  std::uint64_t k = 0;
  for (auto _ : state) {
    const double now = static_cast<double>(k++) / 1000.0;
    times.time([&] { controller.tick(now); });
    benchmark::DoNotOptimize(controller.commanded().data());
  }
  times.report(state, show_name);
}
void BM_TickBehaviourLayers(benchmark::State& state) { idle_bench_show(state, "lively-head"); }
void BM_TickClipLayers(benchmark::State& state) { idle_bench_show(state, "layered-head"); }
BENCHMARK(BM_TickBehaviourLayers)->Iterations(120000);
BENCHMARK(BM_TickClipLayers)->Iterations(120000);

}  // namespace

BENCHMARK_MAIN();
