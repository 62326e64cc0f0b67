#include "avar/playback/runtime/orientation_keys.hpp"

#include <cmath>
#include <string>

#include "avar/core/format.hpp"

namespace avar::playback {

std::optional<OrientationInterpolation> orientation_interpolation_from_name(std::string_view name) {
  if (name == "slerp") return OrientationInterpolation::slerp;
  if (name == "squad") return OrientationInterpolation::squad;
  return std::nullopt;
}

const char* to_string(OrientationInterpolation interpolation) {
  return interpolation == OrientationInterpolation::squad ? "squad" : "slerp";
}

QuaternionTrack OrientationKeyTrack::build(const OrientationKeysSpec& spec) {
  if (spec.keys.empty()) throw InputError(spec.where, "orientation keys: found none; expected at least one key");
  std::vector<QuaternionKey> keys;
  for (std::size_t i = 0; i < spec.keys.size(); ++i) {
    const OrientationKeySpec& k = spec.keys[i];
    if (!std::isfinite(k.time)) throw InputError(k.where, "expected a finite key time (seconds)");
    if (i > 0 && !(k.time > spec.keys[i - 1].time))
      throw InputError(k.where, "orientation key time " + format_number(k.time) + " s does not come after the previous key's " +
                                    format_number(spec.keys[i - 1].time) + " s; expected strictly increasing times");
    if (k.quaternion) {
      const double norm = k.quaternion->norm();
      if (!std::isfinite(norm) || norm == 0)
        throw InputError(k.where, "expected a quaternion [w, x, y, z] of finite numbers, not all 0");
      keys.push_back({k.time, *k.quaternion});
    } else {
      if (!k.euler.allFinite()) throw InputError(k.where, "expected Euler angles [x, y, z] of finite numbers (radians)");
      keys.push_back({k.time, quaternion_from_euler(k.euler, spec.order)});
    }
  }
  return QuaternionTrack(std::move(keys), spec.interpolation);
}

OrientationKeyTrack::OrientationKeyTrack(OrientationKeysSpec spec) : spec_(std::move(spec)), track_(build(spec_)) {}

}  // namespace avar::playback
