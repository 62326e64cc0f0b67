// avar-bench-curves: the cost of one curve sample. A 10-minute curve with about a thousand keys
// is sampled at a 1 kHz tick with its cached cursor (what the sampler does every tick), and at
// random times (binary search). Linear, step and two kinds of Bezier segments: handles at a third
// of the segment (the time cubic degenerates to a line, Blender's linear branch) and handles of
// random length (a full cubic in time, Cardano's or the trigonometric branch).
// ns_per_sample is reported for every run; the repetitions give its median and worst.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <random>
#include <vector>

#include "avar/playback/curve.hpp"

namespace {

using avar::playback::Curve;
using avar::playback::CurveCursor;
using avar::playback::Handle;
using avar::playback::Interpolation;
using avar::playback::RawCurve;
using avar::playback::RawKey;

constexpr double kLength = 600.0;  // seconds
constexpr double kTick = 0.001;    // 1 kHz
constexpr std::size_t kRandomTimes = 1 << 16;

enum Kind { kLinear, kStep, kBezierThirds, kBezierFree };

Curve long_curve(Kind kind) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> times;
  for (double t = 0; t <= kLength; t += 0.2 + 0.8 * u(rng)) times.push_back(t);
  RawCurve raw;
  for (std::size_t i = 0; i < times.size(); ++i) {
    RawKey k;
    k.time = times[i];
    k.value = -90 + 180 * u(rng);
    switch (kind) {
      case kLinear: k.interpolation = Interpolation::linear; break;
      case kStep: k.interpolation = Interpolation::step; break;
      case kBezierThirds:
      case kBezierFree: k.interpolation = Interpolation::bezier; break;
    }
    const double before = i > 0 ? times[i] - times[i - 1] : 1.0;
    const double after = i + 1 < times.size() ? times[i + 1] - times[i] : 1.0;
    const double slope = -20 + 40 * u(rng);
    const double left = kind == kBezierFree ? (0.1 + 0.5 * u(rng)) * before : before / 3;
    const double right = kind == kBezierFree ? (0.1 + 0.5 * u(rng)) * after : after / 3;
    k.left = Handle{k.time - left, k.value - slope * left};
    k.right = Handle{k.time + right, k.value + slope * right};
    raw.keys.push_back(k);
  }
  return Curve::build(raw);
}

void BM_Sequential1kHz(benchmark::State& state, Kind kind) {
  const Curve curve = long_curve(kind);
  const auto samples = static_cast<std::size_t>(kLength / kTick);
  for (auto _ : state) {
    CurveCursor cursor;
    double sum = 0;
    for (std::size_t k = 0; k < samples; ++k) sum += curve.evaluate(static_cast<double>(k) * kTick, cursor);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["keys"] = static_cast<double>(curve.key_count());
  state.counters["ns_per_sample"] =
      benchmark::Counter(static_cast<double>(samples) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_RandomAccess(benchmark::State& state, Kind kind) {
  const Curve curve = long_curve(kind);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, kLength + 1);
  std::vector<double> times(kRandomTimes);
  for (double& t : times) t = u(rng);
  for (auto _ : state) {
    double sum = 0;
    for (double t : times) sum += curve.evaluate(t);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["keys"] = static_cast<double>(curve.key_count());
  state.counters["ns_per_sample"] =
      benchmark::Counter(static_cast<double>(kRandomTimes) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

double worst(const std::vector<double>& v) {
  double m = v.empty() ? 0 : v.front();
  for (double x : v) m = x > m ? x : m;
  return m;
}

void repeated(benchmark::internal::Benchmark* b) {
  b->Repetitions(5)->ComputeStatistics("worst", worst)->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_Sequential1kHz, linear, kLinear)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, step, kStep)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, bezier_thirds, kBezierThirds)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, bezier_free, kBezierFree)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, linear, kLinear)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, step, kStep)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, bezier_thirds, kBezierThirds)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, bezier_free, kBezierFree)->Apply(repeated);

}  // namespace

BENCHMARK_MAIN();
