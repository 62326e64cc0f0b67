#include "avar/kinematics/jacobian.hpp"

#include <cassert>

namespace avar::kinematics {

void geometric_jacobian(const Model& model, const Workspace& ws, std::size_t effector,
                        Eigen::Ref<Eigen::Matrix<double, 6, Eigen::Dynamic>> J) noexcept {
  assert(J.cols() == static_cast<Eigen::Index>(model.dof()));
  assert(effector < model.effector_count());
  assert(ws.joint_count() == model.joint_count());
  J.setZero();
  const Effector& e = model.effector(effector);
  const Eigen::Vector3d tip = (ws.joint_pose(e.joint) * e.tool).translation();
  // Only the joints on the path from the effector's joint up to the base move the effector.
  for (std::size_t i = e.joint; i != Joint::kNoParent; i = model.joint(i).parent) {
    const Joint& joint = model.joint(i);
    if (!joint.movable()) continue;
    const Eigen::Isometry3d& frame = ws.joint_pose(i);
    const Eigen::Vector3d axis = frame.linear() * joint.axis;
    const auto column = static_cast<Eigen::Index>(joint.q_index);
    if (joint.type == JointType::revolute) {
      J.block<3, 1>(0, column) = axis.cross(tip - frame.translation());
      J.block<3, 1>(3, column) = axis;
    } else {
      J.block<3, 1>(0, column) = axis;
    }
  }
}

}  // namespace avar::kinematics
