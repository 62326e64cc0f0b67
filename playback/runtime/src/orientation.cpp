#include "avar/playback/runtime/orientation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::playback {
namespace {

struct OrderInfo {
  EulerOrder order;
  const char* name;
  std::array<int, 3> axes;  ///< axis indices in the order they are applied
};
constexpr std::array<OrderInfo, 6> kOrders = {{{EulerOrder::xyz, "xyz", {0, 1, 2}},
                                               {EulerOrder::xzy, "xzy", {0, 2, 1}},
                                               {EulerOrder::yxz, "yxz", {1, 0, 2}},
                                               {EulerOrder::yzx, "yzx", {1, 2, 0}},
                                               {EulerOrder::zxy, "zxy", {2, 0, 1}},
                                               {EulerOrder::zyx, "zyx", {2, 1, 0}}}};

const OrderInfo& info(EulerOrder order) { return kOrders[static_cast<std::size_t>(order)]; }

Eigen::Vector3d axis(int index) { return Eigen::Vector3d::Unit(index); }

/// The rotation vector v with exp(v) = q (v = axis * angle / 2), for a unit quaternion.
Eigen::Vector3d log_of(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.axis() * (0.5 * aa.angle());
}

Eigen::Quaterniond exp_of(const Eigen::Vector3d& v) {
  const double half_angle = v.norm();
  if (half_angle < 1e-300) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(2 * half_angle, v / half_angle));
}

}  // namespace

std::optional<EulerOrder> euler_order_from_name(std::string_view name) {
  for (const auto& o : kOrders)
    if (name == o.name) return o.order;
  return std::nullopt;
}

const char* to_string(EulerOrder order) { return info(order).name; }

Eigen::Matrix3d matrix_from_euler(const Eigen::Vector3d& xyz, EulerOrder order) noexcept {
  return quaternion_from_euler(xyz, order).toRotationMatrix();
}

Eigen::Quaterniond quaternion_from_euler(const Eigen::Vector3d& xyz, EulerOrder order) noexcept {
  const auto& a = info(order).axes;
  // Applied first = rightmost factor: R = R_a2 R_a1 R_a0.
  return Eigen::Quaterniond(Eigen::AngleAxisd(xyz[a[2]], axis(a[2])) * Eigen::AngleAxisd(xyz[a[1]], axis(a[1])) *
                            Eigen::AngleAxisd(xyz[a[0]], axis(a[0])));
}

Eigen::Vector3d euler_from_matrix(const Eigen::Matrix3d& rotation, EulerOrder order) noexcept {
  const auto& a = info(order).axes;
  // Eigen's eulerAngles(i, j, k) gives (e0, e1, e2) with R = R_i(e0) R_j(e1) R_k(e2), e0 in
  // [0, pi]; re-express it with the middle angle in [-pi/2, pi/2] (the other solution of the
  // same rotation for Tait-Bryan orders: (e0 - pi, pi - e1, e2 - pi) up to sign conventions).
  Eigen::Vector3d e = rotation.eulerAngles(a[2], a[1], a[0]);
  if (e[1] > M_PI / 2 || e[1] < -M_PI / 2) {
    e[0] += M_PI;
    e[1] = M_PI - e[1];
    e[2] += M_PI;
  }
  for (int i = 0; i < 3; ++i) e[i] = std::remainder(e[i], 2 * M_PI);
  // The candidate may differ by the sign of the middle axis' pi turn; keep whichever rebuilds R.
  Eigen::Vector3d xyz;
  xyz[a[2]] = e[0];
  xyz[a[1]] = e[1];
  xyz[a[0]] = e[2];
  if (!matrix_from_euler(xyz, order).isApprox(rotation, 1e-9)) {
    const Eigen::Vector3d raw = rotation.eulerAngles(a[2], a[1], a[0]);
    xyz[a[2]] = raw[0];
    xyz[a[1]] = raw[1];
    xyz[a[0]] = raw[2];
  }
  return xyz;
}

Eigen::Vector3d euler_from_quaternion(const Eigen::Quaterniond& q, EulerOrder order) noexcept {
  return euler_from_matrix(q.normalized().toRotationMatrix(), order);
}

QuaternionTrack::QuaternionTrack(std::vector<QuaternionKey> keys, OrientationInterpolation interpolation)
    : keys_(std::move(keys)), interpolation_(interpolation) {
  if (keys_.empty()) throw std::invalid_argument("orientation track: expected at least one key");
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    auto& k = keys_[i];
    if (!std::isfinite(k.time)) throw std::invalid_argument("orientation track: key time is not finite");
    if (i > 0 && !(k.time > keys_[i - 1].time))
      throw std::invalid_argument("orientation track: key times must strictly increase");
    const double norm = k.rotation.norm();
    if (!std::isfinite(norm) || norm == 0)
      throw std::invalid_argument("orientation track: a rotation is not a finite non-zero quaternion");
    k.rotation.coeffs() /= norm;
    if (i > 0 && k.rotation.dot(keys_[i - 1].rotation) < 0) k.rotation.coeffs() = -k.rotation.coeffs();
  }
  inner_.resize(keys_.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const Eigen::Quaterniond& q = keys_[i].rotation;
    if (i == 0 || i + 1 == keys_.size()) {
      inner_[i] = q;
      continue;
    }
    const Eigen::Quaterniond inverse = q.conjugate();
    const Eigen::Vector3d sum = log_of(inverse * keys_[i + 1].rotation) + log_of(inverse * keys_[i - 1].rotation);
    inner_[i] = q * exp_of(-0.25 * sum);
    if (inner_[i].dot(q) < 0) inner_[i].coeffs() = -inner_[i].coeffs();
  }
}

namespace {
std::vector<QuaternionKey> from_euler(const std::vector<EulerKey>& keys, EulerOrder order) {
  std::vector<QuaternionKey> out;
  out.reserve(keys.size());
  for (const auto& k : keys) {
    if (!k.xyz_radians.allFinite()) throw std::invalid_argument("orientation track: an Euler angle is not finite");
    out.push_back({k.time, quaternion_from_euler(k.xyz_radians, order)});
  }
  return out;
}

}  // namespace

QuaternionTrack::QuaternionTrack(const std::vector<EulerKey>& keys, EulerOrder order, OrientationInterpolation interpolation)
    : QuaternionTrack(from_euler(keys, order), interpolation) {}

Eigen::Quaterniond QuaternionTrack::evaluate(double t) const noexcept {
  if (!(t > keys_.front().time)) return keys_.front().rotation;
  if (t >= keys_.back().time) return keys_.back().rotation;
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), t, [](double x, const QuaternionKey& k) { return x < k.time; });
  const std::size_t i = static_cast<std::size_t>(it - keys_.begin()) - 1;
  const double u = (t - keys_[i].time) / (keys_[i + 1].time - keys_[i].time);
  const Eigen::Quaterniond& a = keys_[i].rotation;
  const Eigen::Quaterniond& b = keys_[i + 1].rotation;
  if (interpolation_ == OrientationInterpolation::slerp) return a.slerp(u, b).normalized();
  const Eigen::Quaterniond outer = a.slerp(u, b);
  const Eigen::Quaterniond inner = inner_[i].slerp(u, inner_[i + 1]);
  return outer.slerp(2 * u * (1 - u), inner).normalized();
}

}  // namespace avar::playback
