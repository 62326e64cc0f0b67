#include "avar/kinematics/workspace.hpp"

namespace avar::kinematics {

Workspace::Workspace(const Model& model) : joint_poses_(model.joint_count(), Eigen::Isometry3d::Identity()) {}

}  // namespace avar::kinematics
