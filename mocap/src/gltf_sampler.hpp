#pragma once
// A glTF 2.0 animation sampler evaluated at any time, as the specification defines it
// (Appendix C, interpolation): STEP, LINEAR (spherical linear for rotations) and CUBICSPLINE
// (cubic Hermite, tangents scaled by the key interval). Before the first key the first value
// holds, after the last the last. Private to the glTF reader.

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace avar::mocap::gltf {

enum class Interpolation : std::uint8_t { step, linear, cubic_spline };

struct KeyedSampler {
  Interpolation interpolation = Interpolation::linear;
  int components = 3;         ///< 3 (translation, scale) or 4 (rotation quaternion x, y, z, w)
  std::vector<double> times;  ///< seconds, strictly increasing, at least one
  /// components values per key; for CUBICSPLINE three elements per key: in-tangent, value,
  /// out-tangent (the spec's layout).
  std::vector<double> values;
};

/// The sampler's value at time `t` (seconds): components 3 in xyz, components 4 a quaternion
/// in (x, y, z, w) order. Rotations come out normalised.
Eigen::Vector4d sample(const KeyedSampler& sampler, double t);

}  // namespace avar::mocap::gltf
