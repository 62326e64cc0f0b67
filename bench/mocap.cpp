// avar-bench-mocap: loading a several-MB BVH file (60 joints, 3 rotation channels each plus the
// root's 3 positions, 5000 frames: about 6 MB, generated at start with seeded values) from text
// and from a file, and forward kinematics of every frame. Peer: reading the same MOTION rows with
// an std::istringstream >> double loop (the usual hand-written reader), numbers only, no model.
// The repetitions give the median and the worst.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "avar/mocap/bvh_reader.hpp"

namespace {

constexpr int kBenchJoints = 60;
constexpr int kBenchFrames = 5000;

/// A chain of 60 joints under a root, ZXY rotation channels, an End Site at the tip.
std::string bench_bvh_text() {
  std::string text =
      "HIERARCHY\nROOT j0\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n";
  for (int j = 1; j < kBenchJoints; ++j)
    text += "JOINT j" + std::to_string(j) + "\n{\n  OFFSET 0 1.5 0.25\n  CHANNELS 3 Zrotation Xrotation Yrotation\n";
  text += "End Site\n{\n  OFFSET 0 1 0\n}\n";
  for (int j = 0; j < kBenchJoints; ++j) text += "}\n";
  text += "MOTION\nFrames: " + std::to_string(kBenchFrames) + "\nFrame Time: 0.008333\n";
  std::mt19937 random(20261203);
  std::uniform_real_distribution<double> angle(-180, 180);
  char number[32];
  for (int f = 0; f < kBenchFrames; ++f) {
    for (int c = 0; c < 3 * kBenchJoints + 3; ++c) {
      std::snprintf(number, sizeof number, c ? " %.4f" : "%.4f", angle(random));
      text += number;
    }
    text += '\n';
  }
  return text;
}

const std::string& bench_text() {
  static const std::string text = bench_bvh_text();
  return text;
}

const std::string& bench_file() {
  static const std::string path = [] {
    std::string p = (std::filesystem::temp_directory_path() / "avar-bench-mocap.bvh").string();
    std::ofstream(p, std::ios::binary) << bench_text();
    return p;
  }();
  return path;
}

void BM_ParseBvhText(benchmark::State& state) {
  bench_text();  // generated outside the timing
  for (auto _ : state) benchmark::DoNotOptimize(avar::mocap::parse_bvh(bench_text(), "bench.bvh"));
  state.counters["MB"] = static_cast<double>(bench_text().size()) / 1e6;
}

void BM_LoadBvhFile(benchmark::State& state) {
  bench_file();  // written outside the timing
  for (auto _ : state) benchmark::DoNotOptimize(avar::mocap::load_bvh(bench_file()));
}

void BM_PeerIstreamNumbers(benchmark::State& state) {
  const std::string rows = bench_text().substr(bench_text().find("Frame Time:") + 20);
  for (auto _ : state) {
    std::istringstream in(rows);
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(kBenchFrames) * (3 * kBenchJoints + 3));
    for (double v = 0; in >> v;) values.push_back(v);
    benchmark::DoNotOptimize(values.data());
  }
}

void BM_ForwardKinematicsAllFrames(benchmark::State& state) {
  const avar::mocap::SkeletonAnimation animation = avar::mocap::parse_bvh(bench_text(), "bench.bvh");
  std::vector<Eigen::Affine3d> world;
  for (auto _ : state)
    for (const auto& pose : animation.frames) {
      avar::mocap::forward_kinematics(animation, pose, world);
      benchmark::DoNotOptimize(world.data());
    }
  state.counters["ns_per_frame"] =
      benchmark::Counter(static_cast<double>(animation.frame_count()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

double bench_worst(const std::vector<double>& v) {
  double m = v.empty() ? 0 : v.front();
  for (double x : v) m = x > m ? x : m;
  return m;
}

void bench_repeated(benchmark::internal::Benchmark* b) {
  b->Repetitions(5)->ComputeStatistics("worst", bench_worst)->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_ParseBvhText)->Apply(bench_repeated);
BENCHMARK(BM_LoadBvhFile)->Apply(bench_repeated);
BENCHMARK(BM_PeerIstreamNumbers)->Apply(bench_repeated);
BENCHMARK(BM_ForwardKinematicsAllFrames)->Apply(bench_repeated);

}  // namespace

BENCHMARK_MAIN();
