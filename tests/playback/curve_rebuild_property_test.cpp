// Curve::build(raw, previous, previous_raw), the rebuild after an edit that copies the segments
// the edit left alone, against Curve::build(raw) over seeded random Bezier curves (free, auto,
// auto_clamped, vector and aligned handles, easing and linear keys among them) and random edits
// of them: a key moved, added, removed, its handle type or interpolation changed, a run of keys
// shifted as a drag shifts them. Every sample, at the keys, inside every segment, on both sides of
// them and through the extrapolation, is the same bits.
#include <gtest/gtest.h>

#include <cstddef>
#include <random>
#include <vector>

#include "avar/core/bit_cast.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

constexpr unsigned kRebuildSeeds[] = {3u, 11u, 2026u, 77777u};
constexpr HandleType kRebuildTypes[] = {HandleType::automatic, HandleType::auto_clamped, HandleType::vector, HandleType::aligned,
                                        HandleType::free};

RawKey rebuild_test_key(std::mt19937& rng, double t) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto pick = rng() % 10;
  RawKey k = key(t, -90 + 180 * u(rng),
                 pick == 0   ? Interpolation::linear
                 : pick == 1 ? Interpolation::sine
                             : Interpolation::bezier);
  k.left_type = kRebuildTypes[rng() % 5];
  k.right_type = kRebuildTypes[rng() % 5];
  // Free and aligned sides need their handle; the others ignore a given one.
  k.left = Handle{t - 0.02 - 0.2 * u(rng), k.value - 40 + 80 * u(rng)};
  k.right = Handle{t + 0.02 + 0.2 * u(rng), k.value - 40 + 80 * u(rng)};
  return k;
}

RawCurve rebuild_test_curve(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<RawKey> keys;
  double t = 0;
  for (std::size_t i = 0; i < n; ++i) {
    keys.push_back(rebuild_test_key(rng, t));
    t += 0.1 + 0.5 * u(rng);
  }
  RawCurve raw = raw_curve(std::move(keys));
  if (rng() % 3 == 0) raw.extrapolation = Extrapolation::linear;
  return raw;
}

/// Shifts key i (and its handles) by dt, dv.
void shift_key(RawKey& k, double dt, double dv) {
  k.time += dt, k.value += dv;
  if (k.left) k.left->time += dt, k.left->value += dv;
  if (k.right) k.right->time += dt, k.right->value += dv;
}

/// One random edit that keeps the keys in strictly increasing time.
RawCurve edited_curve(std::mt19937& rng, RawCurve raw) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<RawKey>& keys = raw.keys;
  const std::size_t i = rng() % keys.size();
  switch (rng() % 6) {
    case 0: {  // a key moved in value, or in time within its neighbours
      const double lo = i > 0 ? keys[i - 1].time : keys[i].time - 1,
                   hi = i + 1 < keys.size() ? keys[i + 1].time : keys[i].time + 1;
      shift_key(keys[i], (lo + (hi - lo) * (0.1 + 0.8 * u(rng))) - keys[i].time, -10 + 20 * u(rng));
      break;
    }
    case 1:  // a key added between two, or after the last
      if (i + 1 < keys.size())
        keys.insert(keys.begin() + static_cast<std::ptrdiff_t>(i + 1),
                    rebuild_test_key(rng, 0.5 * (keys[i].time + keys[i + 1].time)));
      else keys.push_back(rebuild_test_key(rng, keys[i].time + 0.3));
      break;
    case 2:  // a key removed
      if (keys.size() > 2) keys.erase(keys.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    case 3: keys[i].left_type = kRebuildTypes[rng() % 5], keys[i].right_type = kRebuildTypes[rng() % 5]; break;
    case 4:
      keys[i].interpolation = keys[i].interpolation == Interpolation::bezier ? Interpolation::linear : Interpolation::bezier;
      break;
    default: {  // a drag: a run of keys shifted together, the keys after them too (order kept)
      const double dt = 0.05 * u(rng), dv = -3 + 6 * u(rng);
      for (std::size_t j = i; j < keys.size(); ++j) shift_key(keys[j], dt, j < i + 20 ? dv : 0);
      break;
    }
  }
  return raw;
}

/// Every sample the two curves can differ at: the keys, 1 us on both sides, seven points inside
/// every segment, and a second beyond both ends.
void expect_same_rebuilt_samples(const Curve& a, const Curve& b, const RawCurve& raw, unsigned seed, int edit) {
  std::vector<double> times{raw.keys.front().time - 1, raw.keys.back().time + 1};
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const double t = raw.keys[i].time;
    times.insert(times.end(), {t, t - 1e-6, t + 1e-6});
    if (i + 1 < raw.keys.size())
      for (int j = 1; j < 8; ++j) times.push_back(t + (raw.keys[i + 1].time - t) * j / 8.0);
  }
  ASSERT_EQ(a.key_count(), b.key_count());
  for (const double t : times)
    ASSERT_TRUE(same_bits(a.evaluate(t), b.evaluate(t)))
        << "seed " << seed << ", edit " << edit << ", t = " << t << ": rebuilt " << a.evaluate(t) << ", built " << b.evaluate(t);
}

TEST(CurveRebuild, EqualsAFreshBuildBitForBitOverRandomEdits) {
  for (const unsigned seed : kRebuildSeeds) {
    std::mt19937 rng(seed);
    RawCurve raw = rebuild_test_curve(rng, 40);
    Curve curve = Curve::build(raw);
    for (int e = 0; e < 200; ++e) {
      RawCurve next = edited_curve(rng, raw);
      Curve rebuilt = Curve::build(next, curve, raw);
      expect_same_rebuilt_samples(rebuilt, Curve::build(next), next, seed, e);
      raw = std::move(next);
      curve = std::move(rebuilt);
    }
  }
}

TEST(CurveRebuild, FromAnUnrelatedCurveIsStillAFreshBuild) {
  std::mt19937 rng(5);
  const RawCurve a = rebuild_test_curve(rng, 30), b = rebuild_test_curve(rng, 17);
  expect_same_rebuilt_samples(Curve::build(b, Curve::build(a), a), Curve::build(b), b, 5, 0);
  // A previous curve that was not built from previous_raw (the wrong key count) is not trusted.
  expect_same_rebuilt_samples(Curve::build(b, Curve::build(b), a), Curve::build(b), b, 5, 1);
}

}  // namespace
}  // namespace avar::playback
