// DistanceTime::from_keys: a user distance-time function built from keys and checked by sampling
// (the offline half of distance_time.hpp).
#include <string>

#include "avar/core/format.hpp"
#include "avar/playback/runtime/distance_time.hpp"

namespace avar::playback {

DistanceTime DistanceTime::from_keys(const RawCurve& raw) {
  DistanceTime f(DistanceTimeShape::linear);
  f.shape_ = DistanceTimeShape::user;
  f.user_raw_ = raw;
  f.user_ = Curve::build(raw);
  const auto& keys = raw.keys;
  const std::string what = "a user distance-time curve (normalised time -> normalised distance)";
  if (keys.front().time != 0 || keys.front().value != 0)
    throw InputError(keys.front().where, "expected " + what + " to start with a key at time 0, value 0; found time " +
                                             format_number(keys.front().time) + ", value " + format_number(keys.front().value));
  if (keys.size() < 2 || keys.back().time != 1 || keys.back().value != 1)
    throw InputError(keys.back().where, "expected " + what + " to end with a key at time 1, value 1; found time " +
                                            format_number(keys.back().time) + ", value " + format_number(keys.back().value));
  for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
    double previous = keys[k].value;
    for (int i = 1; i <= kUserSamplesPerSegment; ++i) {
      const double t = keys[k].time + (keys[k + 1].time - keys[k].time) * i / kUserSamplesPerSegment;
      const double s = f.user_.evaluate(t);
      if (s < previous || s < 0 || s > 1)
        throw InputError(keys[k].where, "expected " + what + " to rise from 0 to 1 without ever going back, but between " +
                                            format_number(keys[k].time) + " and " + format_number(keys[k + 1].time) +
                                            " it reaches " + format_number(s) + " at " + format_number(t) + " after " +
                                            format_number(previous));
      previous = s;
    }
  }
  return f;
}

}  // namespace avar::playback
