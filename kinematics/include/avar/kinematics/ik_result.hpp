#pragma once
// The graded outcome of an inverse-kinematics solve. Real-time safe: plain values.

#include <string_view>

namespace avar::kinematics {

enum class IkStatus {
  converged,  ///< every goal is within the tolerances
  degraded,   ///< not within tolerance, but the solver stopped at a stationary point of the
              ///< weighted error within the limits: the closest reachable pose it found
              ///< (e.g. an unreachable target); usable, `position_error`/`orientation_error` say how far
  failed,     ///< invalid input, or the iteration budget ran out while the error was still falling;
              ///< the output is still within limits (the best iterate, or the clamped seed)
};

struct [[nodiscard]] IkResult {
  IkStatus status = IkStatus::failed;
  int iterations = 0;           ///< error evaluations (forward kinematics runs) spent, over all restarts
  double position_error = 0;    ///< m: largest |component| of any goal's position error at the output
  double orientation_error = 0; ///< rad: largest |component| of any goal's orientation error, or aim angle
};

constexpr std::string_view to_string(IkStatus s) noexcept {
  switch (s) {
    case IkStatus::converged: return "converged";
    case IkStatus::degraded: return "degraded";
    case IkStatus::failed: return "failed";
  }
  return "unknown";
}

}  // namespace avar::kinematics
