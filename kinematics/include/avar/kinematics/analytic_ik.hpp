#pragma once
// Closed-form inverse kinematics for the linkages of animatronic figures (Parent, Computer
// Animation, ch. 5): a two-link planar reach and the aim (look-at) of pan/tilt(/roll) heads and
// eyes, including a pair of eyes converging on a near target. Joint limits are always respected:
// a target that needs more is met as closely as the limits allow and graded degraded, with the
// residual. Lengths in metres, angles in radians. Real-time safe: no allocation, no exception,
// no lock; pure functions, callable from any thread.

#include <Eigen/Geometry>

#include "avar/kinematics/ik_result.hpp"

namespace avar::kinematics {

struct JointRange {
  double lower = -3.141592653589793;
  double upper = 3.141592653589793;
};

// ---- Two-link planar reach -------------------------------------------------------------------

/// Two links in the x-y plane of the shoulder frame: the shoulder turns about z at the origin
/// (0 = upper link along +x), the elbow about z at the end of the upper link (0 = straight).
struct TwoLinkArm {
  double upper_length = 0;  ///< m, > 0
  double lower_length = 0;  ///< m, > 0
  JointRange shoulder;
  JointRange elbow;
};

/// Which of the two mirror solutions: `up` bends the elbow clockwise (elbow angle <= 0, the elbow
/// on the +y/left side of the line from shoulder to target), `down` counter-clockwise (>= 0).
enum class ElbowBend { up, down };

struct TwoLinkAngles {
  double shoulder = 0;  ///< rad
  double elbow = 0;     ///< rad
};

/// Angles that put the end of the lower link at `target` (shoulder frame, m; z is ignored).
/// Out of reach (too far or too near) or out of limits: the closest point the chosen bend
/// reaches within the limits, graded degraded with position_error = the remaining distance.
/// Failed (angles 0 clamped) for a non-finite target or non-positive lengths.
IkResult solve_two_link(const TwoLinkArm& arm, const Eigen::Vector2d& target, ElbowBend bend, TwoLinkAngles& out) noexcept;

// ---- Aim: pan/tilt(/roll) heads and eyes ------------------------------------------------------

/// A gimbal whose axes meet at one point, the origin of `mount`: pan about +z, then tilt about
/// the panned +y, then roll about the resulting +x, which is the line of sight (at zero it is
/// +x of `mount`). A positive tilt turns the sight down (from +x toward -z).
struct PanTiltHead {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  ///< gimbal frame -> parent frame
  JointRange pan;
  JointRange tilt;
  JointRange roll;  ///< unused by a pan/tilt head
};

struct PanTiltRollAngles {
  double pan = 0;   ///< rad
  double tilt = 0;  ///< rad
  double roll = 0;  ///< rad
};

/// Angles that point the line of sight at `target` (parent frame of the mount, m), roll set to
/// `roll` (clamped). When the limits do not allow it, the sight direction closest to the target
/// within them; degraded, orientation_error = the angle left between the sight and the target.
/// Failed (angles 0 clamped) for a non-finite input or a target at the gimbal centre.
IkResult aim_head(const PanTiltHead& head, const Eigen::Vector3d& target, PanTiltRollAngles& out, double roll = 0) noexcept;

/// Two eyes on one head converge on a near target: each eye aims from its own centre, so the
/// two lines of sight meet at the target (vergence). `head_pose` is the world pose of the frame
/// the eyes' mounts are given in; `target` is in the world. The result is the worse of the two.
IkResult aim_eyes(const PanTiltHead& left, const PanTiltHead& right, const Eigen::Isometry3d& head_pose,
                  const Eigen::Vector3d& target, PanTiltRollAngles& left_out, PanTiltRollAngles& right_out) noexcept;

}  // namespace avar::kinematics
