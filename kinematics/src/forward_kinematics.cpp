#include "avar/kinematics/forward_kinematics.hpp"

namespace avar::kinematics {

Workspace::Workspace(const Model& model) : world(model.joints().size(), Eigen::Isometry3d::Identity()) {}

void forward_kinematics(const Model& model, std::span<const double> q, Workspace& ws) noexcept {
  const auto& joints = model.joints();
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const Joint& j = joints[i];
    Eigen::Isometry3d pose = j.parent < 0 ? j.origin : ws.world[static_cast<std::size_t>(j.parent)] * j.origin;
    if (j.type == JointType::revolute)
      pose.rotate(Eigen::AngleAxisd(q[static_cast<std::size_t>(j.q_index)], j.axis));
    else if (j.type == JointType::prismatic)
      pose.translate(q[static_cast<std::size_t>(j.q_index)] * j.axis);
    ws.world[i] = pose;
  }
}

Eigen::Isometry3d effector_pose(const Model& model, const Workspace& ws, std::size_t effector) noexcept {
  const Effector& e = model.effectors()[effector];
  return ws.world[e.joint] * e.tool;
}

void geometric_jacobian(const Model& model, const Workspace& ws, std::size_t effector,
                        Eigen::Ref<Eigen::Matrix<double, 6, Eigen::Dynamic>> J) noexcept {
  J.setZero();
  const Effector& e = model.effectors()[effector];
  const Eigen::Vector3d p = (ws.world[e.joint] * e.tool).translation();
  for (int i = static_cast<int>(e.joint); i >= 0; i = model.joints()[static_cast<std::size_t>(i)].parent) {
    const Joint& j = model.joints()[static_cast<std::size_t>(i)];
    if (j.type == JointType::fixed) continue;
    const Eigen::Isometry3d& frame = ws.world[static_cast<std::size_t>(i)];
    const Eigen::Vector3d z = frame.linear() * j.axis;
    const auto col = static_cast<Eigen::Index>(j.q_index);
    if (j.type == JointType::revolute) {
      J.block<3, 1>(0, col) = z.cross(p - frame.translation());
      J.block<3, 1>(3, col) = z;
    } else {
      J.block<3, 1>(0, col) = z;
    }
  }
}

}  // namespace avar::kinematics
