#include "gltf_sampler.hpp"

#include <algorithm>

namespace avar::mocap::gltf {
namespace {

/// Element `e` (of `stride` elements per key) of key `k`.
Eigen::Vector4d gltf_key_element(const KeyedSampler& s, std::size_t k, std::size_t stride, std::size_t e) {
  Eigen::Vector4d v = Eigen::Vector4d::Zero();
  const auto n = static_cast<std::size_t>(s.components);
  const std::size_t base = (k * stride + e) * n;
  for (std::size_t c = 0; c < n; ++c) v[static_cast<Eigen::Index>(c)] = s.values[base + c];
  return v;
}

Eigen::Quaterniond gltf_as_quaternion(const Eigen::Vector4d& xyzw) { return {xyzw[3], xyzw[0], xyzw[1], xyzw[2]}; }

Eigen::Vector4d gltf_normalised_rotation(const Eigen::Vector4d& v, int components) {
  return components == 4 && v.norm() > 0 ? Eigen::Vector4d(v.normalized()) : v;
}

}  // namespace

Eigen::Vector4d sample(const KeyedSampler& s, double t) {
  const bool cubic = s.interpolation == Interpolation::cubic_spline;
  const std::size_t stride = cubic ? 3 : 1;
  const std::size_t value = cubic ? 1 : 0;  // the value element of a key
  const std::size_t last = s.times.size() - 1;
  if (t <= s.times.front()) return gltf_normalised_rotation(gltf_key_element(s, 0, stride, value), s.components);
  if (t >= s.times.back()) return gltf_normalised_rotation(gltf_key_element(s, last, stride, value), s.components);
  // k: the last key at or before t; t lies in [t_k, t_k+1).
  const auto k = static_cast<std::size_t>(std::upper_bound(s.times.begin(), s.times.end(), t) - s.times.begin()) - 1;
  const double t0 = s.times[k], t1 = s.times[k + 1];
  const double td = t1 - t0;
  const double u = (t - t0) / td;
  switch (s.interpolation) {
    case Interpolation::step: return gltf_key_element(s, k, 1, 0);
    case Interpolation::linear: {
      const Eigen::Vector4d a = gltf_key_element(s, k, 1, 0), b = gltf_key_element(s, k + 1, 1, 0);
      if (s.components != 4) return a + u * (b - a);
      // The spec's slerp turns the short way, as Eigen's does (the model's evaluate uses it too).
      const Eigen::Quaterniond q = gltf_as_quaternion(a).normalized().slerp(u, gltf_as_quaternion(b).normalized()).normalized();
      return {q.x(), q.y(), q.z(), q.w()};
    }
    case Interpolation::cubic_spline: {
      // p(u) = (2u^3 - 3u^2 + 1) v_k + td (u^3 - 2u^2 + u) b_k + (-2u^3 + 3u^2) v_k+1 + td (u^3 - u^2) a_k+1
      const double u2 = u * u, u3 = u2 * u;
      const Eigen::Vector4d p =
          (2 * u3 - 3 * u2 + 1) * gltf_key_element(s, k, 3, 1) + td * (u3 - 2 * u2 + u) * gltf_key_element(s, k, 3, 2) +
          (-2 * u3 + 3 * u2) * gltf_key_element(s, k + 1, 3, 1) + td * (u3 - u2) * gltf_key_element(s, k + 1, 3, 0);
      return gltf_normalised_rotation(p, s.components);
    }
  }
  return gltf_key_element(s, k, stride, value);
}

}  // namespace avar::mocap::gltf
