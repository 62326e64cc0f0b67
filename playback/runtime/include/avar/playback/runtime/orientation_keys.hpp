#pragma once
// Orientation keys of a target as authored in a show: each key a unit quaternion [w, x, y, z] or
// Euler angles (x, y, z radians in the track's stated order, orientation.hpp's convention),
// interpolated on the sphere by slerp or squad (QuaternionTrack). The authored keys are kept so the
// show can be written back exactly.

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/orientation.hpp"

namespace avar::playback {

/// "slerp", "squad"; nullopt otherwise.
std::optional<OrientationInterpolation> orientation_interpolation_from_name(std::string_view name);
const char* to_string(OrientationInterpolation interpolation);

struct OrientationKeySpec {
  double time = 0;  ///< seconds in the show
  /// The key as a quaternion; when empty, the key is `euler`.
  std::optional<Eigen::Quaterniond> quaternion;
  Eigen::Vector3d euler = Eigen::Vector3d::Zero();  ///< radians about x, y, z in the track's order
  SourceLocation where;
};

struct OrientationKeysSpec {
  EulerOrder order = EulerOrder::xyz;
  OrientationInterpolation interpolation = OrientationInterpolation::slerp;
  std::vector<OrientationKeySpec> keys;
  SourceLocation where;
};

class OrientationKeyTrack {
 public:
  /// Validates and builds. Throws InputError at the offending key when there are no keys, times
  /// are not finite and strictly increasing, Euler angles are not finite, or a quaternion is not
  /// finite with a non-zero norm. Load time: allocates.
  explicit OrientationKeyTrack(OrientationKeysSpec spec);

  /// Unit quaternion at show time t (seconds); the end keys hold outside them. Real-time safe,
  /// thread-safe.
  Eigen::Quaterniond evaluate(double t) const noexcept { return track_.evaluate(t); }
  const OrientationKeysSpec& spec() const noexcept { return spec_; }

 private:
  static QuaternionTrack build(const OrientationKeysSpec& spec);
  OrientationKeysSpec spec_;
  QuaternionTrack track_;
};

}  // namespace avar::playback
