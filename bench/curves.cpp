// avar-bench-curves: the cost of one curve sample. A 10-minute curve with about a thousand keys
// is sampled at a 1 kHz tick with its cached cursor (what the sampler does every tick), and at
// random times (binary search). Linear, step and two kinds of Bezier segments: handles at a third
// of the segment (time is linear in the curve parameter: no time solve) and handles of random
// length (a full cubic in time: the tabulated inverse, or Blender's closed form where time nearly
// stalls); Blender's auto handles with continuous-acceleration smoothing (their time handles sit
// at thirds too); a sine easing; Catmull-Rom; a uniform cubic B-spline, and the very same
// B-spline in Eigen's spline module (unsupported/Eigen/Splines) as the peer (checked to agree
// with avar's before timing).
// ns_per_sample is reported for every run; the repetitions give its median and worst.
#include <benchmark/benchmark.h>

#include <unsupported/Eigen/Splines>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "avar/playback/runtime/curve.hpp"

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

enum Kind { kLinear, kStep, kBezierThirds, kBezierFree, kBezierAutoSmooth, kSine, kCatmullRom, kBspline };
constexpr double kBsplineSpacing = 0.5;  // B-spline keys are evenly spaced, as the uniform spline assumes

RawCurve long_raw(Kind kind) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> times;
  if (kind == kBspline)
    for (double t = 0; t <= kLength; t += kBsplineSpacing) times.push_back(t);
  else
    for (double t = 0; t <= kLength; t += 0.2 + 0.8 * u(rng)) times.push_back(t);
  RawCurve raw;
  if (kind == kBezierAutoSmooth) raw.auto_smoothing = avar::playback::AutoSmoothing::continuous_acceleration;
  for (std::size_t i = 0; i < times.size(); ++i) {
    RawKey k;
    k.time = times[i];
    k.value = -90 + 180 * u(rng);
    switch (kind) {
      case kLinear: k.interpolation = Interpolation::linear; break;
      case kStep: k.interpolation = Interpolation::step; break;
      case kBezierThirds:
      case kBezierFree:
      case kBezierAutoSmooth: k.interpolation = Interpolation::bezier; break;
      case kSine: k.interpolation = Interpolation::sine; break;
      case kCatmullRom: k.interpolation = Interpolation::catmull_rom; break;
      case kBspline: k.interpolation = Interpolation::bspline; break;
    }
    const double before = i > 0 ? times[i] - times[i - 1] : 1.0;
    const double after = i + 1 < times.size() ? times[i + 1] - times[i] : 1.0;
    const double slope = -20 + 40 * u(rng);
    const double left = kind == kBezierFree ? (0.1 + 0.5 * u(rng)) * before : before / 3;
    const double right = kind == kBezierFree ? (0.1 + 0.5 * u(rng)) * after : after / 3;
    if (kind == kBezierThirds || kind == kBezierFree) {
      k.left = Handle{k.time - left, k.value - slope * left};
      k.right = Handle{k.time + right, k.value + slope * right};
    } else {
      k.left_type = k.right_type = avar::playback::HandleType::automatic;
    }
    raw.keys.push_back(k);
  }
  return raw;
}

Curve long_curve(Kind kind) { return Curve::build(long_raw(kind)); }

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

// The avar B-spline's control points (key values, reflected once beyond each end) with a uniform
// knot vector in seconds: Eigen's spline over the same data and the same time domain.
using EigenSpline = Eigen::Spline<double, 1, 3>;
EigenSpline eigen_bspline(const Curve& curve) {
  std::vector<double> p;
  for (const RawKey& k : long_raw(kBspline).keys) p.push_back(k.value);
  const auto n = static_cast<Eigen::Index>(p.size());
  EigenSpline::ControlPointVectorType points(1, n + 2);
  points(0, 0) = 2 * p.front() - p[1];
  for (Eigen::Index j = 0; j < n; ++j) points(0, j + 1) = p[static_cast<std::size_t>(j)];
  points(0, n + 1) = 2 * p.back() - p[p.size() - 2];
  EigenSpline::KnotVectorType knots(n + 6);
  for (Eigen::Index j = 0; j < n + 6; ++j) knots(j) = static_cast<double>(j - 3) * kBsplineSpacing;
  EigenSpline spline(knots, points);
  for (double t = 0; t < curve.end_time(); t += 0.0371) {
    if (std::abs(spline(t)(0) - curve.evaluate(t)) > 1e-9) {
      std::fprintf(stderr, "Eigen's spline and avar's B-spline disagree at %g s: %g vs %g\n", t, spline(t)(0), curve.evaluate(t));
      std::abort();
    }
  }
  return spline;
}

void BM_EigenSplineSequential1kHz(benchmark::State& state) {
  const Curve curve = long_curve(kBspline);
  const EigenSpline spline = eigen_bspline(curve);
  const double end = curve.end_time();
  const auto samples = static_cast<std::size_t>(end / kTick);
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t k = 0; k < samples; ++k) sum += spline(static_cast<double>(k) * kTick)(0);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ns_per_sample"] =
      benchmark::Counter(static_cast<double>(samples) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_EigenSplineRandomAccess(benchmark::State& state) {
  const Curve curve = long_curve(kBspline);
  const EigenSpline spline = eigen_bspline(curve);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, curve.end_time());
  std::vector<double> times(kRandomTimes);
  for (double& t : times) t = u(rng);
  for (auto _ : state) {
    double sum = 0;
    for (double t : times) sum += spline(t)(0);
    benchmark::DoNotOptimize(sum);
  }
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
BENCHMARK_CAPTURE(BM_Sequential1kHz, bezier_auto_smooth, kBezierAutoSmooth)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, sine, kSine)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, catmull_rom, kCatmullRom)->Apply(repeated);
BENCHMARK_CAPTURE(BM_Sequential1kHz, bspline, kBspline)->Apply(repeated);
BENCHMARK(BM_EigenSplineSequential1kHz)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, linear, kLinear)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, step, kStep)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, bezier_thirds, kBezierThirds)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, bezier_free, kBezierFree)->Apply(repeated);
BENCHMARK_CAPTURE(BM_RandomAccess, bspline, kBspline)->Apply(repeated);
BENCHMARK(BM_EigenSplineRandomAccess)->Apply(repeated);

}  // namespace

BENCHMARK_MAIN();
