#pragma once
// How an inverse-kinematics solve iterates. Plain values; real-time safe to copy.

#include <cstdint>
#include <span>

namespace avar::kinematics {

enum class IkMethod {
  /// Levenberg-Marquardt damped least squares: dq = (J^T J + lambda I)^-1 J^T e, the damping
  /// adapted to the error (Sugihara) and raised after any step that does not lower it, so it
  /// stays well-conditioned near singularities and takes Gauss-Newton steps near the solution.
  /// A joint on a limit that the step would push past it is taken out of that step, so the
  /// other joints make up for it (this matters on redundant arms with tight limits).
  damped_least_squares,
  /// Pseudo-inverse through the SVD (singular values below a floor are dropped) with a secondary
  /// task in the null space: pull toward IkOptions::preferred, dq += (I - J+ J) gain (preferred - q).
  pseudo_inverse,
  /// Jacobian transpose with Buss's optimal step length: dq = alpha J^T e.
  jacobian_transpose,
  /// Cyclic coordinate descent: each joint in turn, tip to base, moved to its best value alone.
  cyclic_coordinate_descent,
};

struct IkOptions {
  IkMethod method = IkMethod::damped_least_squares;
  int max_iterations = 100;             ///< per attempt, in error evaluations (FK runs)
  double position_tolerance = 1e-5;     ///< m, per component of every position error
  double orientation_tolerance = 1e-5;  ///< rad, per component of every orientation error (aim: the angle)
  /// Attempts from random configurations (drawn within limits) after the first one from the seed
  /// fails to converge; the best attempt is returned. 0 for per-tick tracking, where the seed is
  /// the previous solution; a few help a cold start. The draws come from a generator in the
  /// IkWorkspace, so results repeat for the same workspace history.
  int restarts = 0;
  /// Preferred configuration for the pseudo-inverse null-space task (size dof, or empty for none).
  /// The span must stay valid for the duration of the solve.
  std::span<const double> preferred{};
  double null_space_gain = 0.5;  ///< per iteration, 0..1
};

/// The production default for per-tick tracking, chosen by measurement (bench/ik.cpp, reported
/// in issue 4): damped least squares, limits projected every iterate, no restarts.
constexpr IkOptions default_ik_options() noexcept { return IkOptions{}; }

/// The default for a cold start (no previous solution near the goal): the same, with up to 20
/// random restarts; it costs more only when the first attempt does not converge.
constexpr IkOptions cold_start_ik_options() noexcept {
  IkOptions options;
  options.restarts = 20;
  return options;
}

}  // namespace avar::kinematics
