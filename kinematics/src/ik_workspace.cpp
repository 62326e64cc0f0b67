#include "avar/kinematics/ik_workspace.hpp"

namespace avar::kinematics {

IkWorkspace::IkWorkspace(const Model& model, std::size_t max_goals, std::uint64_t restart_seed)
    : fk(model),
      J(static_cast<Eigen::Index>(6 * max_goals), static_cast<Eigen::Index>(model.dof())),
      J_effector(6, static_cast<Eigen::Index>(model.dof())),
      e(static_cast<Eigen::Index>(6 * max_goals)),
      e_kept(static_cast<Eigen::Index>(6 * max_goals)),
      A(static_cast<Eigen::Index>(model.dof()), static_cast<Eigen::Index>(model.dof())),
      g(static_cast<Eigen::Index>(model.dof())),
      dq(static_cast<Eigen::Index>(model.dof())),
      q(static_cast<Eigen::Index>(model.dof())),
      q_trial(static_cast<Eigen::Index>(model.dof())),
      q_best(static_cast<Eigen::Index>(model.dof())),
      llt(static_cast<Eigen::Index>(model.dof())),
      svd(static_cast<Eigen::Index>(6 * max_goals), static_cast<Eigen::Index>(model.dof()),
          Eigen::ComputeThinU | Eigen::ComputeThinV),
      moves(model.joint_count() * model.effector_count(), 0),
      rng(restart_seed),
      max_goals_(max_goals) {
  J.setZero();
  e.setZero();
  for (std::size_t effector = 0; effector < model.effector_count(); ++effector)
    for (std::size_t i = model.effector(effector).joint; i != Joint::kNoParent; i = model.joint(i).parent)
      moves[i * model.effector_count() + effector] = 1;
}

}  // namespace avar::kinematics
