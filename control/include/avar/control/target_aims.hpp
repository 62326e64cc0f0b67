#pragma once
// Targets held by hand: a puppeteer (the studio's 3-D view, a live control) puts an inverse-
// kinematics target of the show at a point, and the IK stage solves for that point instead of the
// show's path until it is let go; the joints follow within their channels' limits, as they follow
// any target. Indexed by the show's target, in the show's order.
//
// Loop thread only (the session applies aim commands there between ticks); real-time safe: fixed
// capacity, no allocation.

#include <array>
#include <cstddef>

#include <Eigen/Core>

namespace avar::control {

class TargetAims {
 public:
  /// The most targets a show can have held at once (a figure's gaze and hands, with room).
  static constexpr std::size_t kCapacity = 16;

  /// Holds target `index` at `point` (metres, the rig's base frame); false when `index` is past
  /// kCapacity or the point is not finite.
  bool aim(std::size_t index, const Eigen::Vector3d& point) noexcept {
    if (index >= kCapacity || !point.allFinite()) return false;
    held_[index] = true;
    points_[index] = point;
    return true;
  }
  /// Lets target `index` follow the show again.
  void release(std::size_t index) noexcept {
    if (index < kCapacity) held_[index] = false;
  }
  bool held(std::size_t index) const noexcept { return index < kCapacity && held_[index]; }
  const Eigen::Vector3d& point(std::size_t index) const noexcept { return points_[index]; }

 private:
  std::array<bool, kCapacity> held_{};
  std::array<Eigen::Vector3d, kCapacity> points_{};
};

}  // namespace avar::control
