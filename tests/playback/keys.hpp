#pragma once
// Building keys and curves in playback tests.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/track.hpp"

namespace avar::playback::testing {

/// A key placed at "test.yaml:<line>:5", so that errors can be checked for their location.
inline RawKey key(double t, double v, Interpolation i = Interpolation::linear, std::optional<Handle> left = {},
                  std::optional<Handle> right = {}, int line = 1) {
  RawKey k;
  k.time = t;
  k.value = v;
  k.interpolation = i;
  k.left = left;
  k.right = right;
  k.where = {"test.yaml", line, 5};
  return k;
}

inline RawCurve raw_curve(std::vector<RawKey> keys) {
  RawCurve raw;
  raw.keys = std::move(keys);
  raw.where = {"test.yaml", 1, 3};
  return raw;
}

inline Curve build(std::vector<RawKey> keys) { return Curve::build(raw_curve(std::move(keys))); }

/// A track of `channel` built from keys, without a source location.
inline Track track(const std::string& channel, std::vector<RawKey> keys) {
  RawCurve raw = raw_curve(std::move(keys));
  Curve curve = Curve::build(raw);
  return Track{channel, std::move(raw), std::move(curve), {}};
}

}  // namespace avar::playback::testing
