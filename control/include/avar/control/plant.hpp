#pragma once
// The two seams between the loop and a simulated (or externally measured) figure.

#include <span>

namespace avar::control {

/// Positions measured apart from the links' own reports: a simulator's ground truth, external
/// encoders, a motion-capture system.
class PositionSource {
 public:
  virtual ~PositionSource() = default;
  /// Writes each known position (channel units) to measured[channel] and sets known[channel];
  /// leaves the other entries. Real-time safe; on the loop thread.
  virtual void measure(std::span<double> measured, std::span<bool> known) const noexcept = 0;
};

/// What the loop drives when the figure is simulated: after every tick the runner advances it
/// by the tick's period, on the loop thread, outside the tick. Not real-time.
class Plant {
 public:
  virtual ~Plant() = default;
  virtual void advance(double dt_s) = 0;
};

}  // namespace avar::control
