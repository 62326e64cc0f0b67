// The device engine against avar's double engine (the reference, Blender-exact): every golden
// curve of tests/playback/golden and 10^5 seeded random curves of every interpolation, easing,
// handle type, extrapolation and Cycles family, encoded as device images and sampled at integer
// ticks, within 1 unit of the 16-bit output everywhere (before, between, at and after the keys).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "avar/config/show_file.hpp"
#include "avar/device/curve_engine.hpp"
#include "avar/device/show_export.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace avar::device {
namespace {

using playback::Curve;
using playback::Interpolation;
using playback::RawCurve;
using playback::RawKey;

/// The reference's 16-bit output: the double value mapped over the range, rounded, saturated.
int reference_output(double value, OutputRange range) {
  const double o = std::round(range.to_output(value));
  return static_cast<int>(std::clamp(o, 0.0, 65535.0));
}

struct Comparison {
  std::size_t samples = 0;
  std::size_t mismatches = 0;  ///< samples more than 1 unit apart
  int worst = 0;
  double worst_time = 0;
};

/// Samples the encoded curve every `step` ticks over [from, to] ticks, in order and then again
/// out of order (the cache must not change a result), against the reference.
Comparison compare(const RawCurve& raw, const Curve& curve, OutputRange range, std::uint32_t tps, std::int64_t from,
                   std::int64_t to, std::int64_t step) {
  const std::vector<std::uint8_t> image = single_channel_image(encode_channel_record(raw, curve, range, tps), tps, 0);
  Channel channel;
  ShowHeader header;
  EXPECT_EQ(check_image(image.data(), static_cast<std::uint32_t>(image.size()), header), kImageOk)
      << to_string(raw.keys.front().interpolation);
  EXPECT_TRUE(open_channel(image.data(), static_cast<std::uint32_t>(image.size()), 0, channel));
  SegmentCache cache;
  reset_cache(cache);
  SegmentCache jumping;
  reset_cache(jumping);
  Comparison c;
  for (std::int64_t tick = from; tick <= to; tick += step) {
    const auto t = static_cast<std::int32_t>(tick);
    const int device = sample(channel, cache, t);
    const int expected = reference_output(curve.evaluate(static_cast<double>(tick) / tps), range);
    const int error = std::abs(device - expected);
    ++c.samples;
    if (error > 1) ++c.mismatches;
    if (error > c.worst) c.worst = error, c.worst_time = static_cast<double>(tick) / tps;
    // The same tick reached from far away (the mirror image of the window): the same bits.
    const auto mirrored = static_cast<std::int32_t>(from + to - tick);
    sample(channel, jumping, mirrored);
    EXPECT_EQ(sample(channel, jumping, t), device) << "tick " << tick;
  }
  return c;
}

// Every golden curve over the golden window (-2 s to the show's end + 2 s), at 2.4 kHz, on a
// range that covers it with a margin, and on a narrow range that makes the output saturate.
TEST(DeviceCurveAccuracy, EveryGoldenCurveIsWithinOneUnit) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/tests/playback/golden/blender_curves.yaml");
  ASSERT_EQ(show.tracks.size(), 50u);
  std::size_t samples = 0;
  for (const playback::Track& track : show.tracks) {
    double low = 1e300, high = -1e300;
    for (double t = -2; t <= show.duration + 2; t += 1.0 / 480) {
      low = std::min(low, track.curve.evaluate(t)), high = std::max(high, track.curve.evaluate(t));
    }
    const double margin = std::max(1.0, 0.05 * (high - low));
    std::vector<double> times = {1.0 / 2400};
    for (const RawKey& k : track.raw.keys) times.push_back(k.time);
    const std::uint32_t tps = choose_ticks_per_second(times);
    EXPECT_EQ(tps, 24000u) << track.channel;
    for (const OutputRange range :
         {OutputRange{low - margin, high + margin}, OutputRange{(3 * low + high) / 4, (low + 3 * high) / 4}}) {
      const Comparison c = compare(track.raw, track.curve, range, tps, -2 * static_cast<std::int64_t>(tps),
                                   static_cast<std::int64_t>((show.duration + 2) * tps), 10);
      EXPECT_EQ(c.mismatches, 0u) << track.channel << ": worst " << c.worst << " units at " << c.worst_time << " s";
      samples += c.samples;
    }
  }
  EXPECT_GT(samples, 900000u);
}

// A random curve of one family: 2 to 6 keys on a frame grid, values within +-100, the family's
// parameters random within what Blender and avar accept.
struct Family {
  Interpolation interpolation;
  std::string handles;  ///< bezier: auto, auto_clamped, vector, free, aligned, mixed
};

RawCurve random_curve(std::mt19937& rng, const Family& family, double frame) {
  std::uniform_real_distribution<double> u(0, 1);
  const int n = 2 + static_cast<int>(rng() % 5);
  std::vector<RawKey> keys;
  std::int64_t f = static_cast<std::int64_t>(rng() % 20) - 10;
  for (int i = 0; i < n; ++i) {
    RawKey k;
    k.time = static_cast<double>(f) * frame;
    k.value = -100 + 200 * u(rng);
    k.interpolation = family.interpolation;
    k.easing = static_cast<playback::Easing>(rng() % 4);
    k.where = {"random.yaml", i + 1, 5};
    if (family.interpolation == Interpolation::back) k.back = 3 * u(rng);
    if (family.interpolation == Interpolation::elastic) {
      k.amplitude = u(rng) < 0.3 ? 0.0 : 300 * u(rng);
      k.period = u(rng) < 0.4 ? 0.0 : 0.05 + u(rng);
    }
    if (family.interpolation == Interpolation::hermite) k.in_slope = -200 + 400 * u(rng), k.out_slope = -200 + 400 * u(rng);
    if (family.interpolation == Interpolation::cardinal || family.interpolation == Interpolation::kochanek_bartels)
      k.tension = -1 + 2 * u(rng);
    if (family.interpolation == Interpolation::kochanek_bartels) k.continuity = -1 + 2 * u(rng), k.bias = -1 + 2 * u(rng);
    keys.push_back(k);
    // The splines' tangents follow the ratio of neighbouring gaps: kept within 8 (their overshoot
    // within the engine's 16 ranges; the exporter refuses more, with the key).
    f += (playback::is_easing_family(family.interpolation) || family.interpolation == Interpolation::linear ||
                  family.interpolation == Interpolation::step
              ? 1
              : 6) +
         static_cast<std::int64_t>(rng() % 43);
  }
  if (family.interpolation == Interpolation::bezier) {
    using playback::HandleType;
    const HandleType types[] = {HandleType::automatic, HandleType::auto_clamped, HandleType::vector, HandleType::free,
                                HandleType::aligned};
    for (std::size_t i = 0; i < keys.size(); ++i) {
      RawKey& k = keys[i];
      const auto pick = [&]() -> HandleType {
        if (family.handles == "auto") return HandleType::automatic;
        if (family.handles == "auto_clamped") return HandleType::auto_clamped;
        if (family.handles == "vector") return HandleType::vector;
        if (family.handles == "free") return HandleType::free;
        if (family.handles == "aligned") return HandleType::aligned;
        return types[rng() % 5];
      };
      k.left_type = pick();
      k.right_type = k.left_type == HandleType::aligned || family.handles != "mixed" ? *k.left_type : pick();
      // Free and aligned sides need their handle: forward in time (up to 1.2 of the gap, which
      // Blender's correction shortens), any value within +-100 of the key.
      const double before = i > 0 ? k.time - keys[i - 1].time : 1.0,
                   after = i + 1 < keys.size() ? keys[i + 1].time - k.time : 1.0;
      const double slope = -300 + 600 * u(rng);
      const double left = (0.05 + 1.15 * u(rng)) * before, right = (0.05 + 1.15 * u(rng)) * after;
      k.left =
          playback::Handle{k.time - left, k.value - (*k.left_type == HandleType::aligned ? slope * left : -100 + 200 * u(rng))};
      k.right = playback::Handle{k.time + right,
                                 k.value + (*k.right_type == HandleType::aligned ? slope * right : -100 + 200 * u(rng))};
    }
  }
  RawCurve raw(std::move(keys), {"random.yaml", 1, 3});
  const int ends = static_cast<int>(rng() % 4);
  raw.extrapolation = ends % 2 ? playback::Extrapolation::linear : playback::Extrapolation::constant;
  if (ends >= 2) {
    raw.cycles.before = static_cast<playback::CycleMode>(rng() % 4);
    raw.cycles.after = static_cast<playback::CycleMode>(rng() % 4);
    raw.cycles.before_count = static_cast<int>(rng() % 3);
    raw.cycles.after_count = static_cast<int>(rng() % 3);
  }
  if (family.interpolation == Interpolation::bezier && rng() % 2)
    raw.auto_smoothing = playback::AutoSmoothing::continuous_acceleration;
  return raw;
}

// 10^5 curves spread over every family, each sampled at about 40 ticks within and 4 s around
// its keys; every sample within 1 unit. The few whose handles lie beyond the engine's bounds (16
// ranges) must be refused for that reason.
TEST(DeviceCurveAccuracy, RandomCurvesOfEveryFamilyAreWithinOneUnit) {
  std::vector<Family> families;
  for (int i = 0; i <= static_cast<int>(Interpolation::bspline); ++i)
    if (static_cast<Interpolation>(i) != Interpolation::bezier) families.push_back({static_cast<Interpolation>(i), ""});
  for (const char* h : {"auto", "auto_clamped", "vector", "free", "aligned", "mixed"})
    families.push_back({Interpolation::bezier, h});
  const double frames[] = {1.0 / 24, 1.0 / 25, 1.0 / 30, 1.0 / 60, 0.001};
  constexpr int kCurves = 100000;
  std::mt19937 rng(20261207);
  std::map<std::string, Comparison> by_family;
  int failed_curves = 0;
  int refused = 0;
  for (int i = 0; i < kCurves; ++i) {
    const Family& family = families[static_cast<std::size_t>(i) % families.size()];
    const RawCurve raw = random_curve(rng, family, frames[rng() % 5]);
    const Curve curve = Curve::build(raw);
    std::vector<double> times;
    for (const RawKey& k : raw.keys) times.push_back(k.time);
    const std::uint32_t tps = choose_ticks_per_second(times);
    const OutputRange range{-150, 150};
    const auto start = static_cast<std::int64_t>(std::llround((raw.keys.front().time - 2) * tps));
    const auto span = static_cast<std::int64_t>(std::llround((raw.keys.back().time - raw.keys.front().time + 4) * tps));
    const std::int64_t step = std::max<std::int64_t>(1, span / 40 + static_cast<std::int64_t>(rng() % 7));
    Comparison c;
    try {
      c = compare(raw, curve, range, tps, start, start + span, step);
    } catch (const InputError& e) {
      // Refused only when a control point of the curve lies beyond the engine's 16 ranges.
      bool beyond = false;
      for (std::size_t j = 0; j < curve.segment_count(); ++j) {
        const Curve::SegmentView v = curve.segment_view(j);
        for (const double p : {v.v0, v.v0 + v.e1 / 3, v.v0 + (2 * v.e1 + v.e2) / 3})
          beyond = beyond || std::abs(range.to_output(p)) > (1 << 20);
      }
      EXPECT_TRUE(beyond) << "curve " << i << " (" << to_string(family.interpolation) << " " << family.handles
                          << ") refused: " << e.what();
      EXPECT_NE(std::string(e.what()).find("more than 16 times the channel's range"), std::string::npos) << e.what();
      ++refused;
      continue;
    }
    Comparison& total =
        by_family[std::string(playback::to_string(family.interpolation)) + (family.handles.empty() ? "" : " " + family.handles)];
    total.samples += c.samples;
    total.mismatches += c.mismatches;
    if (c.worst > total.worst) total.worst = c.worst, total.worst_time = c.worst_time;
    if (c.mismatches != 0)
      ADD_FAILURE() << "curve " << i << " (" << to_string(family.interpolation) << " " << family.handles << "): worst " << c.worst
                    << " units at " << c.worst_time << " s";
    if (c.mismatches != 0 && ++failed_curves >= 20) break;
  }
  // Curves whose handles reach more than 16 ranges (aligned beside steep auto handles) are rare.
  EXPECT_LE(refused, kCurves / 1000);
  for (const auto& [name, c] : by_family) {
    EXPECT_EQ(c.mismatches, 0u) << name;
    EXPECT_GT(c.samples, 10000u) << name;
  }
}

}  // namespace
}  // namespace avar::device
