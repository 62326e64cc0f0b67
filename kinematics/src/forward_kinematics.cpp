#include "avar/kinematics/forward_kinematics.hpp"

#include <cassert>
#include <cmath>

namespace avar::kinematics {

Status forward_kinematics(const Model& model, std::span<const double> q, Workspace& ws) noexcept {
  assert(q.size() == model.dof());
  assert(ws.joint_count() == model.joint_count());
  for (const double value : q)
    if (!std::isfinite(value)) return Status::not_finite;

  // Parents come first, so each parent's world pose is ready when its children need it.
  for (std::size_t i = 0; i < model.joint_count(); ++i) {
    const Joint& joint = model.joint(i);
    Eigen::Isometry3d pose = joint.on_base() ? joint.origin : ws.joint_poses_[joint.parent] * joint.origin;
    if (joint.type == JointType::revolute && joint.axis == Eigen::Vector3d::UnitZ()) {
      // The common case (every DH joint, most URDF joints): R RotZ(q) mixes only two columns.
      const double c = std::cos(q[joint.q_index]), s = std::sin(q[joint.q_index]);
      const Eigen::Vector3d x = pose.linear().col(0), y = pose.linear().col(1);
      pose.linear().col(0) = c * x + s * y;
      pose.linear().col(1) = c * y - s * x;
    } else if (joint.type == JointType::revolute)
      pose.linear() = pose.linear() * Eigen::AngleAxisd(q[joint.q_index], joint.axis).toRotationMatrix();
    else if (joint.type == JointType::prismatic)
      pose.translation() += pose.linear() * (q[joint.q_index] * joint.axis);
    ws.joint_poses_[i] = pose;
  }
  return Status::ok;
}

Eigen::Isometry3d effector_pose(const Model& model, const Workspace& ws, std::size_t effector) noexcept {
  assert(effector < model.effector_count());
  const Effector& e = model.effector(effector);
  return ws.joint_pose(e.joint) * e.tool;
}

}  // namespace avar::kinematics
