#pragma once
// What a live performance (puppeteering, idle behaviour) adds to the show: the controller hands
// it the show's frame every running tick, after inverse kinematics and before the limiter, so
// whatever it mixes in still passes the limits and the supervisor.

#include <span>

namespace avar::control {

class LiveLayer {
 public:
  virtual ~LiveLayer() = default;
  /// Mixes into `frame` (channel units, indexed by channel; in: the show's values, out: the
  /// mixed values) at loop time now_s (seconds, growing by the tick period). Called on the loop
  /// thread; real-time safe: no allocation, lock, exception or blocking.
  virtual void apply(double now_s, std::span<double> frame) noexcept = 0;
};

}  // namespace avar::control
