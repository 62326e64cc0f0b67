#pragma once
// Retargeting a skeleton animation onto a rig: which source joints drive which rig channels (a
// joint's rotation about one Euler axis) and which IK targets (a joint's position). The map is
// plain data; config/retarget_map.hpp reads and validates it against a rig, and retarget()
// samples the animation through it. Offline (load time): allocates, may throw.
//
// Rotation onto a channel, per sample: r = the joint's local rotation relative to its rest
// rotation (rest^-1 * q) or to its first frame (q0^-1 * q); (x, y, z) = Euler angles of r in the
// stated order (playback::euler_from_quaternion, R = Rc Rb Ra for order "abc", fixed axes),
// unwrapped across samples so that an angle that passes ±180° keeps going instead of jumping;
// angle = the stated axis's, in the stated unit (deg or rad);
//   value = (reverse ? -1 : 1) * scale * angle + offset          (channel units)
//
// Position onto an IK target, per sample: p = the joint's world position (forward kinematics, file
// units and axes), minus the origin joint's world position when one is named; then
//   rig[i] = sign_i * p[from_i] * source_units * scale + offset[i]   (metres, rig base frame)

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "avar/core/input_error.hpp"
#include "avar/mocap/skeleton_animation.hpp"
#include "avar/playback/runtime/orientation.hpp"

namespace avar::mocap {

enum class RelativeTo { rest, first_frame };
enum class AngleUnit { deg, rad };

struct RotationBinding {
  std::string joint;  ///< source joint name
  SourceLocation joint_where;
  std::string channel;  ///< rig channel name
  int axis = 0;         ///< which Euler angle: 0 x, 1 y, 2 z
  playback::EulerOrder order = playback::EulerOrder::xyz;
  RelativeTo relative_to = RelativeTo::rest;
  double scale = 1;
  double offset = 0;  ///< channel units
  bool reverse = false;
  AngleUnit units = AngleUnit::deg;  ///< the angle's unit before scale and offset
  SourceLocation where;
};

struct PositionBinding {
  std::string joint;  ///< source joint name
  SourceLocation joint_where;
  std::string target;  ///< effector of the rig's kinematics
  double scale = 1;    ///< on top of RetargetMap::source_units
  std::string origin;  ///< joint the position is measured from; empty: the file's origin
  SourceLocation origin_where;
  std::array<int, 3> from{0, 1, 2};                  ///< rig axis i takes file axis from[i]
  std::array<double, 3> sign{1, 1, 1};               ///< ... times sign[i] (+1 or -1)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< metres, rig base frame, added last
  SourceLocation where;
};

struct RetargetMap {
  double source_units = 1;  ///< metres per file unit (positions)
  std::vector<RotationBinding> rotations;
  std::vector<PositionBinding> positions;
  std::string file;  ///< where it was read from (messages)
};

/// A channel's value for one relative rotation (no unwrapping): the formula above.
double rotation_value(const RotationBinding& binding, const Eigen::Quaterniond& relative) noexcept;

/// The rig-frame point for a file-frame position (relative to the origin joint already).
Eigen::Vector3d position_value(const PositionBinding& binding, double source_units,
                               const Eigen::Vector3d& file_position) noexcept;

/// The animation sampled through the map at evenly spaced times.
struct RetargetedMotion {
  std::vector<double> times;  ///< seconds from 0 to the animation's duration, both included
  struct Channel {
    std::string channel;
    std::vector<double> values;  ///< per time, channel units
    std::size_t binding = 0;     ///< index into RetargetMap::rotations
  };
  struct Target {
    std::string target;
    std::array<std::vector<double>, 3> xyz;  ///< per time, metres in the rig's base frame
    std::size_t binding = 0;                 ///< index into RetargetMap::positions
  };
  std::vector<Channel> channels;  ///< in map order
  std::vector<Target> targets;    ///< in map order
};

/// Checks that every joint the map names exists in the animation (InputError at the name in the
/// map, listing the animation's joints), then samples the animation at `sample_rate_hz` (> 0;
/// the last sample sits at the duration) by evaluate() and applies the map. `progress`, when
/// given, is called with the fraction done (0 to 1) now and then.
RetargetedMotion retarget(const SkeletonAnimation& animation, const RetargetMap& map, double sample_rate_hz,
                          void (*progress)(double fraction, void* context) = nullptr, void* context = nullptr);

}  // namespace avar::mocap
