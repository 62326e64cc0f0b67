#include "avar/kinematics/analytic_ik.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avar::kinematics {
namespace {

double clamp(double value, const JointRange& range) noexcept { return std::clamp(value, range.lower, range.upper); }

/// The nearest representation of `angle` (mod 2 pi) to the middle of the range, so that a
/// range such as [0, 2 pi] still accepts an angle given in (-pi, pi].
double wrap_into(double angle, const JointRange& range) noexcept {
  const double middle = 0.5 * (range.lower + range.upper);
  return angle + 2 * std::numbers::pi * std::round((middle - angle) / (2 * std::numbers::pi));
}

Eigen::Vector2d reach(const TwoLinkArm& arm, const TwoLinkAngles& a) noexcept {
  return {arm.upper_length * std::cos(a.shoulder) + arm.lower_length * std::cos(a.shoulder + a.elbow),
          arm.upper_length * std::sin(a.shoulder) + arm.lower_length * std::sin(a.shoulder + a.elbow)};
}

/// The shoulder angle that points the arm, with this elbow angle, at `target`'s direction.
double shoulder_for(const TwoLinkArm& arm, double elbow, const Eigen::Vector2d& target) noexcept {
  return std::atan2(target.y(), target.x()) -
         std::atan2(arm.lower_length * std::sin(elbow), arm.upper_length + arm.lower_length * std::cos(elbow));
}

IkResult graded(double position_error, double orientation_error) noexcept {
  constexpr double kExact = 1e-9;
  const bool exact = position_error <= kExact && orientation_error <= kExact;
  return {exact ? IkStatus::converged : IkStatus::degraded, 0, position_error, orientation_error};
}

Eigen::Vector3d sight(const PanTiltRollAngles& a) noexcept {
  return {std::cos(a.pan) * std::cos(a.tilt), std::sin(a.pan) * std::cos(a.tilt), -std::sin(a.tilt)};
}

}  // namespace

IkResult solve_two_link(const TwoLinkArm& arm, const Eigen::Vector2d& target, ElbowBend bend, TwoLinkAngles& out) noexcept {
  out = {clamp(0, arm.shoulder), clamp(0, arm.elbow)};
  if (!target.allFinite() || !(arm.upper_length > 0) || !(arm.lower_length > 0) || !std::isfinite(arm.upper_length) ||
      !std::isfinite(arm.lower_length))
    return {IkStatus::failed, 0, 0, 0};
  const double l1 = arm.upper_length, l2 = arm.lower_length;
  // Law of cosines; a distance out of [|l1 - l2|, l1 + l2] is reached as closely as the arm can.
  const double distance = std::clamp(target.norm(), std::abs(l1 - l2), l1 + l2);
  const double cosine = std::clamp((distance * distance - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1.0, 1.0);
  const double bend_angle = std::acos(cosine);
  out.elbow = clamp(wrap_into(bend == ElbowBend::down ? bend_angle : -bend_angle, arm.elbow), arm.elbow);
  // With the elbow fixed (perhaps by its limit), the best shoulder points the arm at the target.
  const Eigen::Vector2d aim = target.norm() > 0 ? target : Eigen::Vector2d::UnitX();
  out.shoulder = clamp(wrap_into(shoulder_for(arm, out.elbow, aim), arm.shoulder), arm.shoulder);
  return graded((reach(arm, out) - target).norm(), 0);
}

IkResult aim_head(const PanTiltHead& head, const Eigen::Vector3d& target, PanTiltRollAngles& out, double roll) noexcept {
  out = {clamp(0, head.pan), clamp(0, head.tilt), clamp(0, head.roll)};
  const Eigen::Vector3d d = head.mount.inverse() * target;
  if (!d.allFinite() || !std::isfinite(roll) || d.norm() < 1e-12) return {IkStatus::failed, 0, 0, 0};
  const Eigen::Vector3d want = d.normalized();
  // Pan toward the target's azimuth; with the pan fixed (perhaps by a limit), the best tilt is the
  // target's elevation in the panned x-z plane.
  out.pan = clamp(wrap_into(std::atan2(want.y(), want.x()), head.pan), head.pan);
  const double forward = std::cos(out.pan) * want.x() + std::sin(out.pan) * want.y();
  out.tilt = clamp(wrap_into(std::atan2(-want.z(), forward), head.tilt), head.tilt);
  out.roll = clamp(roll, head.roll);
  const double miss = std::atan2(sight(out).cross(want).norm(), sight(out).dot(want));
  return graded(0, miss);
}

IkResult aim_eyes(const PanTiltHead& left, const PanTiltHead& right, const Eigen::Isometry3d& head_pose,
                  const Eigen::Vector3d& target, PanTiltRollAngles& left_out, PanTiltRollAngles& right_out) noexcept {
  const Eigen::Vector3d local = head_pose.inverse() * target;
  const IkResult l = aim_head(left, local, left_out);
  const IkResult r = aim_head(right, local, right_out);
  const IkStatus worst = std::max(l.status, r.status);
  return {worst, 0, std::max(l.position_error, r.position_error), std::max(l.orientation_error, r.orientation_error)};
}

}  // namespace avar::kinematics
