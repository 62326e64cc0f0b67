#pragma once
// Orientations (Parent, Computer Animation, 3.3): conversions between unit quaternions, rotation
// matrices and Euler angles with a stated rotation order, and quaternion key tracks interpolated
// by slerp or by Shoemake's squad. Quaternion algebra is Eigen's (Eigen::Quaterniond).
//
// Euler convention (Blender's): angles are radians about x, y and z, stored as (x, y, z) whatever
// the order; order `xyz` rotates about x first, then y, then z, all about the fixed (parent)
// axes, so R = Rz(z) Ry(y) Rx(x). In general, order "abc" means R = Rc Rb Ra.
// Conversions are pure: no allocation, exception or lock.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace avar::playback {

enum class EulerOrder : std::uint8_t { xyz, xzy, yxz, yzx, zxy, zyx };

/// "xyz", "xzy", "yxz", "yzx", "zxy", "zyx"; nullopt for anything else.
std::optional<EulerOrder> euler_order_from_name(std::string_view name);
const char* to_string(EulerOrder order);

Eigen::Matrix3d matrix_from_euler(const Eigen::Vector3d& xyz_radians, EulerOrder order) noexcept;
Eigen::Quaterniond quaternion_from_euler(const Eigen::Vector3d& xyz_radians, EulerOrder order) noexcept;
/// Euler angles (x, y, z) of a rotation matrix in `order`. The middle rotation's angle lies in
/// [-pi/2, pi/2], the others in [-pi, pi]; at gimbal lock (middle angle +-pi/2) one of the
/// others is chosen, so the round trip gives back the rotation, not always the angles.
Eigen::Vector3d euler_from_matrix(const Eigen::Matrix3d& rotation, EulerOrder order) noexcept;
Eigen::Vector3d euler_from_quaternion(const Eigen::Quaterniond& q, EulerOrder order) noexcept;

enum class OrientationInterpolation : std::uint8_t { slerp, squad };

struct QuaternionKey {
  double time = 0;  ///< seconds
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

/// Euler-angle keys: converted to quaternion keys in their stated order, then interpolated on the
/// sphere (never angle by angle, which would depend on the order and could gimbal-lock).
struct EulerKey {
  double time = 0;  ///< seconds
  Eigen::Vector3d xyz_radians = Eigen::Vector3d::Zero();
};

/// An orientation track. Building normalises the keys and flips each key's sign into the same
/// hemisphere as its predecessor (q and -q are the same rotation), so every segment turns the
/// short way (at most pi). Squad uses Shoemake's intermediate points
/// s_i = q_i exp(-(log(q_i^-1 q_{i+1}) + log(q_i^-1 q_{i-1})) / 4) (s = q at the end keys); its
/// angular velocity is continuous at keys in the curve parameter, hence in time where the keys
/// are evenly spaced. Before the first key and after the last the end orientations hold.
class QuaternionTrack {
 public:
  /// Throws std::invalid_argument when there are no keys, times are not finite and strictly
  /// increasing, or a rotation is not finite or has zero norm. Load time: allocates.
  QuaternionTrack(std::vector<QuaternionKey> keys, OrientationInterpolation interpolation);
  QuaternionTrack(const std::vector<EulerKey>& keys, EulerOrder order, OrientationInterpolation interpolation);

  /// Unit quaternion at time t (seconds). Real-time safe: no allocation, exception or lock;
  /// thread-safe (immutable).
  Eigen::Quaterniond evaluate(double t) const noexcept;

  const std::vector<QuaternionKey>& keys() const noexcept { return keys_; }

 private:
  std::vector<QuaternionKey> keys_;
  std::vector<Eigen::Quaterniond> inner_;  ///< squad's s_i
  OrientationInterpolation interpolation_;
};

}  // namespace avar::playback
