#pragma once
// Per-solver scratch for inverse kinematics on one Model: forward-kinematics poses, the stacked
// Jacobian and error, the linear-algebra factorisations and the restart generator, all sized
// once here. Constructing it is the only allocation; solve_ik then allocates nothing. One
// IkWorkspace per thread (it is mutable state); the Model is shared read-only.

#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include <cstddef>
#include <random>
#include <vector>

#include "avar/kinematics/model.hpp"
#include "avar/kinematics/workspace.hpp"

namespace avar::kinematics {

class IkWorkspace {
 public:
  /// Sized for `model` and up to `max_goals` goals per solve (load time: allocates).
  /// `restart_seed` seeds the generator of random restarts.
  explicit IkWorkspace(const Model& model, std::size_t max_goals = 1, std::uint64_t restart_seed = 0x5eed);

  std::size_t max_goals() const noexcept { return max_goals_; }
  std::size_t dof() const noexcept { return static_cast<std::size_t>(q.size()); }
  /// Forward kinematics of the last configuration the solver evaluated (real-time safe to read).
  const Workspace& poses() const noexcept { return fk; }

  // Solver state; the numeric solvers (kinematics/src/ik_*.cpp) use these directly.
  Workspace fk;
  Eigen::MatrixXd J;                         ///< stacked weighted Jacobian, max rows x dof
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_effector;
  Eigen::VectorXd e;                         ///< stacked weighted error, max rows
  Eigen::VectorXd e_kept;                    ///< the error at q while a trial step overwrites e
  Eigen::MatrixXd A;                         ///< dof x dof normal matrix
  Eigen::VectorXd g, dq, q, q_trial, q_best;
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
  std::vector<char> moves;  ///< moves[joint * effectors + effector]: the joint is on the effector's path
  std::mt19937_64 rng;

 private:
  std::size_t max_goals_;
};

}  // namespace avar::kinematics
