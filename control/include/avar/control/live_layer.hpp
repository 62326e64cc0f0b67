#pragma once
// What a live performance (puppeteering, idle behaviour) adds to the show: the controller hands
// it the show's frame every running tick, after inverse kinematics and before the limiter, so
// whatever it mixes in still passes the limits and the supervisor. A layer may also move the
// show's inverse-kinematics goals (a joystick steering a gaze point) before they are solved; the
// joints then follow within their limits as they follow any target.

#include <span>

namespace avar::control {

class LiveLayer {
 public:
  virtual ~LiveLayer() = default;
  /// Mixes into `frame` (channel units, indexed by channel; in: the show's values, out: the
  /// mixed values) at loop time now_s (seconds, growing by the tick period). Called on the loop
  /// thread; real-time safe: no allocation, lock, exception or blocking.
  virtual void apply(double now_s, std::span<double> frame) noexcept = 0;
  /// Mixes into the show's inverse-kinematics goal points before they are solved: `points` holds
  /// x, y, z (metres, the rig's base frame) for every effector of the rig's kinematic model, in
  /// the model's order; in: the show's goals, NaN for effectors no target of the show moves; out:
  /// where the goals go (a NaN or an untouched effector keeps the show's). Called on running
  /// ticks of a show with targets, before apply() and with the same now_s; same thread and
  /// real-time contract. The default moves nothing.
  virtual void apply_targets(double now_s, std::span<double> points) noexcept {
    (void)now_s;
    (void)points;
  }
};

}  // namespace avar::control
