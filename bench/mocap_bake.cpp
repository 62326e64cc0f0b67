// Load + bake time of a several-MB BVH (issue 20): a generated 60-joint skeleton at 120 fps for
// 30 s (about 6 MB of text) read by the BVH reader, then retargeted onto hello-head through a
// four-binding map and fitted (avar mocap bake's work, without writing the file). Reference: the
// bare cost of reading every number of the same file with strtod (a lower bound for any reader).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "avar/config/retarget_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/mocap/bvh_reader.hpp"
#include "avar/config/mocap_bake.hpp"

namespace {

constexpr int kBakeJoints = 60;
constexpr int kBakeFrames = 3600;
constexpr double kBakeFps = 120;

/// Hips, Neck, Head, Jaw, then Bone4..Bone59 hung off the earlier joints as a binary tree.
std::string bake_bench_bvh() {
  const char* names[4] = {"Hips", "Neck", "Head", "Jaw"};
  std::vector<std::vector<int>> children(kBakeJoints);
  for (int j = 1; j < kBakeJoints; ++j) children[static_cast<std::size_t>(j < 4 ? j - 1 : j / 2)].push_back(j);
  std::ostringstream out;
  out << "HIERARCHY\n";
  const auto name = [&](int j) { return j < 4 ? std::string(names[j]) : "Bone" + std::to_string(j); };
  const auto write = [&](const auto& self, int j, int depth) -> void {
    const std::string pad(static_cast<std::size_t>(2 * depth), ' ');
    out << pad << (j == 0 ? "ROOT " : "JOINT ") << name(j) << '\n' << pad << "{\n";
    out << pad << "  OFFSET 0 " << (j == 0 ? 0 : 5) << " 1\n";
    out << pad << "  CHANNELS " << (j == 0 ? "6 Xposition Yposition Zposition " : "3 ") << "Zrotation Xrotation Yrotation\n";
    for (int c : children[static_cast<std::size_t>(j)]) self(self, c, depth + 1);
    if (children[static_cast<std::size_t>(j)].empty())
      out << pad << "  End Site\n" << pad << "  {\n" << pad << "    OFFSET 0 3 0\n" << pad << "  }\n";
    out << pad << "}\n";
  };
  write(write, 0, 0);
  out << "MOTION\nFrames: " << kBakeFrames << "\nFrame Time: " << 1 / kBakeFps << '\n';
  char cell[32];
  for (int f = 0; f < kBakeFrames; ++f) {
    const double t = f / kBakeFps;
    std::string row;
    for (int v = 0; v < 3; ++v) {
      std::snprintf(cell, sizeof cell, "%.4f ", 10 * std::sin(0.3 * t + v));
      row += cell;
    }
    for (int j = 0; j < kBakeJoints; ++j)
      for (int a = 0; a < 3; ++a) {
        // Smooth motion of a few components per channel, within the head's limits.
        const double k = 1 + 0.37 * j + 0.11 * a;
        double deg = 8 * std::sin(0.9 * k * t + a) + 3 * std::sin(2.3 * k * t) + 1.5 * std::sin(5.1 * t + j);
        if (j == 3) deg = a == 1 ? 7 + 6 * std::sin(4 * t) : 0;  // the jaw opens about X only
        std::snprintf(cell, sizeof cell, "%.4f ", deg);
        row += cell;
      }
    row.back() = '\n';
    out << row;
  }
  return out.str();
}

const std::string& bake_bench_file() {
  static const std::string path = [] {
    std::string p = "/tmp/avar-bench-mocap-bake-" + std::to_string(::getpid()) + ".bvh";
    std::ofstream(p) << bake_bench_bvh();
    return p;
  }();
  return path;
}

const std::string& bake_bench_map() {
  static const std::string path = [] {
    std::string p = "/tmp/avar-bench-mocap-bake-" + std::to_string(::getpid()) + "-map.yaml";
    std::ofstream(p) << "retarget:\n  rotations:\n"
                        "    - {joint: Head, channel: neck_pan, axis: y, order: yxz}\n"
                        "    - {joint: Head, channel: neck_tilt, axis: x, order: yxz, scale: 0.5}\n"
                        "    - {joint: Head, channel: neck_roll, axis: z, order: yxz, scale: 0.5}\n"
                        "    - {joint: Jaw, channel: jaw, axis: x, order: yxz}\n";
    return p;
  }();
  return path;
}

void BM_ReadNumbersOnly(benchmark::State& state) {
  std::ifstream in(bake_bench_file());
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  for (auto _ : state) {
    std::ifstream file(bake_bench_file());
    std::string all((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const char* p = all.c_str() + all.find("Frame Time:") + 11;
    double sum = 0;
    char* end = nullptr;
    for (double v = std::strtod(p, &end); end != p; v = std::strtod(p, &end)) {
      sum += v;
      p = end;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["MB"] = static_cast<double>(s.size()) / 1e6;
}

void BM_LoadBvh(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(avar::mocap::load_bvh(bake_bench_file()));
}

void BM_Bake(benchmark::State& state) {
  const avar::rig::Rig rig = avar::config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  const avar::mocap::RetargetMap map = avar::config::load_retarget_map(bake_bench_map(), rig);
  const avar::mocap::SkeletonAnimation animation = avar::mocap::load_bvh(bake_bench_file());
  std::size_t keys = 0;
  for (auto _ : state) {
    const avar::config::Baked baked =
        avar::config::bake_show(animation, map, rig, avar::config::BakeSettings{}, "bench", nullptr);
    keys = 0;
    for (const auto& t : baked.show.tracks) keys += t.raw.keys.size();
  }
  state.counters["keys"] = static_cast<double>(keys);
}

void BM_LoadAndBake(benchmark::State& state) {
  const avar::rig::Rig rig = avar::config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  const avar::mocap::RetargetMap map = avar::config::load_retarget_map(bake_bench_map(), rig);
  for (auto _ : state) {
    const avar::mocap::SkeletonAnimation animation = avar::mocap::load_bvh(bake_bench_file());
    benchmark::DoNotOptimize(avar::config::bake_show(animation, map, rig, avar::config::BakeSettings{}, "bench", nullptr));
  }
}

double bake_bench_worst(const std::vector<double>& v) {
  double m = v.empty() ? 0 : v.front();
  for (double x : v) m = x > m ? x : m;
  return m;
}

void bake_bench_repeated(benchmark::internal::Benchmark* b) {
  b->Repetitions(5)->ComputeStatistics("worst", bake_bench_worst)->Unit(benchmark::kMillisecond)->Iterations(1);
}

BENCHMARK(BM_ReadNumbersOnly)->Apply(bake_bench_repeated);
BENCHMARK(BM_LoadBvh)->Apply(bake_bench_repeated);
BENCHMARK(BM_Bake)->Apply(bake_bench_repeated);
BENCHMARK(BM_LoadAndBake)->Apply(bake_bench_repeated);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::remove(bake_bench_file().c_str());  // the generated files
  std::remove(bake_bench_map().c_str());
  return 0;
}
